// The LCM⇄CAN bridge node: the vehicle's sensors and ESCs as a DroneCAN bus sees them, and
// the ground's commands and the fc's status between LCM and CAN.
//   A3_STATE (vehicle_state_t) → sensor messages with the SensorModel's seeded noise, each on
//     a schedule of whole periods that takes the freshest state at or after its tick
//     (RateSchedule): ahrs.RawIMU 200 Hz (never faster than states come: with the dynamics
//     at 250 Hz it reports on 4 states of 5, at 100 Hz on every state), gnss.Fix2 10 Hz,
//     air_data.StaticPressure 50 Hz (+ StaticTemperature 10 Hz), ahrs.MagneticFieldStrength2
//     50 Hz, power.BatteryInfo 5 Hz. The IMU samples every state (see sensor_frames.hpp).
//   esc.RawCommand (0..8191) → A3_ACTUATORS (throttle 0..1; armed = any rotor commanded,
//     as all-zero RawCommands are what a disarmed DroneCAN autopilot sends).
//   A3_FC_CMD (fc_command_t) → a3.fc.Command, one for one, heartbeats included. The bridge
//     makes no heartbeats of its own: the fc's link-loss failsafe must see the ground fall
//     silent, not the bridge.
//   a3.fc.Status → A3_FC_STATUS (fc_status_t, the refusal reason as its text).
//   NodeStatus at 1 Hz (WARNING while no state has come for state_timeout_us).
// Bad input is counted and logged, never passed on: states with NaN or a non-unit attitude,
// RawCommands with fewer than 4 rotors; commands with non-finite values are counted and
// forwarded (the fc refuses them with a reason the ground can see).
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "bridge/can/can_bus.hpp"
#include "bridge/dronecan/msg/a3_fc.hpp"
#include "bridge/dronecan/msg/esc.hpp"
#include "bridge/dronecan/node.hpp"
#include "bridge/fc/geo.hpp"
#include "bridge/fc/sensor_model.hpp"
#include "bridge/nodes/rate_schedule.hpp"
#include "bridge/nodes/sensor_frames.hpp"
#include "common/node.hpp"

namespace a3::bridge {

struct SensorRates {
  double imu_hz = 200.0;
  double gnss_hz = 10.0;
  double baro_hz = 50.0;
  double temperature_hz = 10.0;
  double mag_hz = 50.0;
  double battery_hz = 5.0;
};

struct BridgeNodeConfig {
  uint8_t node_id = 20;
  Geodetic home = kDefaultHome;
  SensorNoise noise;
  uint64_t seed = 1;
  SensorRates rates;
  int64_t state_timeout_us = 500'000;
  std::string state_channel;      // default A3_STATE
  std::string actuator_channel;   // default A3_ACTUATORS
  std::string command_channel;    // default A3_FC_CMD
  std::string status_channel;     // default A3_FC_STATUS
};

struct BridgeNodeCounters {
  uint64_t states = 0;
  uint64_t states_rejected = 0;   // NaN, non-unit attitude, or out of order
  uint64_t imu = 0, gnss = 0, baro = 0, mag = 0, battery = 0;
  uint64_t esc_frames = 0;        // RawCommands turned into A3_ACTUATORS
  uint64_t esc_rejected = 0;      // fewer than 4 rotors
  uint64_t esc_clamped = 0;       // a negative (reverse) rotor command, taken as 0
  uint64_t commands = 0;          // A3_FC_CMD forwarded (heartbeats included)
  uint64_t commands_nonfinite = 0;
  uint64_t statuses = 0;          // a3.fc.Status forwarded to A3_FC_STATUS
  uint64_t can_publish_failures = 0;
};

class BridgeNode final : public common::Node {
 public:
  // The CAN bus must outlive the node. Throws std::invalid_argument for a bad node ID or rate.
  BridgeNode(CanBus& can, BridgeNodeConfig config);
  ~BridgeNode() override;

  std::string name() const override { return "bridge"; }
  void start(common::Executor& executor, common::Bus& bus) override;
  // Stops receiving and the timers (the executor's thread, or after it stopped).
  void stop();

  BridgeNodeCounters counters() const;  // safe from any thread
  const DroneCanNode& dronecan() const { return dronecan_; }

 private:
  void on_state(const a3lcm::vehicle_state_t& state);
  void on_command(const a3lcm::fc_command_t& command);
  void on_esc(const EscRawCommand& esc);
  void on_status(const FcStatus& status);
  void publish_sensors(const a3lcm::vehicle_state_t& state);
  template <class Msg>
  void publish_can(const Msg& msg, uint8_t priority);
  void update_health();
  void warn(uint64_t count, const std::string& message) const;

  BridgeNodeConfig config_;
  LocalFrame frame_;
  SensorModel sensors_;
  DroneCanNode dronecan_;
  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  std::vector<common::TimerId> timers_;
  ImuIntegrator imu_;
  RateSchedule imu_schedule_, gnss_schedule_, baro_schedule_, temperature_schedule_, mag_schedule_,
      battery_schedule_;
  bool have_state_ = false;
  int64_t last_state_utime_us_ = 0;
  int64_t last_state_rx_us_ = -1;
  double average_power_W_ = 0.0;
  bool have_power_ = false;

  struct AtomicCounters {
    std::atomic<uint64_t> states{0}, states_rejected{0}, imu{0}, gnss{0}, baro{0}, mag{0}, battery{0},
        esc_frames{0}, esc_rejected{0}, esc_clamped{0}, commands{0}, commands_nonfinite{0}, statuses{0},
        can_publish_failures{0};
  } counters_;
};

}  // namespace a3::bridge
