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

#include "a3lcm/actuator_cmd_t.hpp"
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
  // Lockstep (DESIGN.md "Time"): forward each A3_CLOCK grant to the flight controller as an
  // a3.sim.Clock frame, after the sensor frames of that time; on a repeated grant, publish the
  // last A3_ACTUATORS again (the pacer repeats a grant it has no answer to).
  bool forward_sim_clock = false;
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

  // states, states_rejected (NaN, non-unit attitude, or out of order), imu, gnss, baro, mag,
  // battery, esc_frames (RawCommands turned into A3_ACTUATORS), esc_rejected (fewer than 4
  // rotors), esc_clamped (a negative rotor command, taken as 0), commands (A3_FC_CMD forwarded,
  // heartbeats included), commands_nonfinite, statuses (a3.fc.Status forwarded),
  // can_publish_failures, clock_grants (lockstep grants forwarded as a3.sim.Clock).
  const common::CounterSet& counters() const override { return counter_set_; }
  const DroneCanNode& dronecan() const { return dronecan_; }

 private:
  void on_state(const a3lcm::vehicle_state_t& state);
  void on_command(const a3lcm::fc_command_t& command);
  void on_esc(const EscRawCommand& esc);
  void on_status(const FcStatus& status);
  void on_grant(int64_t utime_us);
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

  bool have_actuator_ = false;
  a3lcm::actuator_cmd_t last_actuator_{};
  int64_t last_grant_us_ = -1;

  common::CounterSet counter_set_;
  struct Counters {
    explicit Counters(common::CounterSet& s)
        : states(s.add("states")), states_rejected(s.add("states_rejected")), imu(s.add("imu")),
          gnss(s.add("gnss")), baro(s.add("baro")), mag(s.add("mag")), battery(s.add("battery")),
          esc_frames(s.add("esc_frames")), esc_rejected(s.add("esc_rejected")), esc_clamped(s.add("esc_clamped")),
          commands(s.add("commands")), commands_nonfinite(s.add("commands_nonfinite")),
          statuses(s.add("statuses")), can_publish_failures(s.add("can_publish_failures")),
          clock_grants(s.add("clock_grants")) {}
    common::Counter &states, &states_rejected, &imu, &gnss, &baro, &mag, &battery, &esc_frames, &esc_rejected,
        &esc_clamped, &commands, &commands_nonfinite, &statuses, &can_publish_failures, &clock_grants;
  } counters_{counter_set_};
};

}  // namespace a3::bridge
