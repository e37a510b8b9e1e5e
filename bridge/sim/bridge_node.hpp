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
//   a3.fc.CommandRefused (the fc refused commands from a node that is not a command source) →
//     A3_SAFETY (safety_event_t "command_refused", source "fc"): the fc never uses LCM.
// Only the fc (fc_node_id) drives the vehicle: esc.RawCommand, a3.fc.Status and
// a3.fc.CommandRefused from any other node are refused, counted and reported on A3_SAFETY
// ("command_refused", source "bridge"), at most one event per report interval.
// Bad input is counted and logged, never passed on: states with NaN or a non-unit attitude,
// RawCommands with fewer than 4 rotors; commands with non-finite values are counted and
// forwarded (the fc refuses them with a reason the ground can see).
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "a3lcm/actuator_cmd_t.hpp"
#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/safety_event_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "bridge/can/can_bus.hpp"
#include "bridge/dronecan/msg/a3_fc.hpp"
#include "bridge/dronecan/msg/a3_fc_refusal.hpp"
#include "bridge/dronecan/msg/esc.hpp"
#include "bridge/dronecan/node.hpp"
#include "bridge/fc/geo.hpp"
#include "bridge/nodes/command_sources.hpp"
#include "bridge/sim/rate_schedule.hpp"
#include "bridge/sim/sensor_frames.hpp"
#include "bridge/sim/sensor_model.hpp"
#include "common/channels.hpp"
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
  uint8_t node_id = kDefaultBridgeNodeId;
  // The flight controller: the only node whose esc.RawCommand, a3.fc.Status and
  // a3.fc.CommandRefused the bridge takes.
  uint8_t fc_node_id = kDefaultFcNodeId;
  int64_t refusal_report_interval_us = 1'000'000;  // at most one own "command_refused" event per interval
  Geodetic home = kDefaultHome;
  SensorNoise noise;
  uint64_t seed = 1;
  SensorRates rates;
  int64_t state_timeout_us = 500'000;
  common::VehicleId vehicle = 0;  // whose A3_STATE, A3_ACTUATORS, A3_FC_CMD, A3_FC_STATUS, A3_SAFETY
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
  // Subscribes A3_STATE, A3_FC_CMD (and A3_CLOCK in lockstep); publishes A3_ACTUATORS,
  // A3_FC_STATUS and A3_SAFETY.
  std::optional<common::NodePorts> ports() const override;
  // Stops receiving and the timers (the executor's thread, or after it stopped).
  void stop();

  // states, states_rejected (NaN, non-unit attitude, or out of order), imu, gnss, baro, mag,
  // battery, esc_frames (RawCommands turned into A3_ACTUATORS), esc_rejected (fewer than 4
  // rotors), esc_clamped (a negative rotor command, taken as 0), commands (A3_FC_CMD forwarded,
  // heartbeats included), commands_nonfinite, statuses (a3.fc.Status forwarded),
  // can_publish_failures, clock_grants (lockstep grants forwarded as a3.sim.Clock),
  // rejected_source (esc.RawCommand, a3.fc.Status or a3.fc.CommandRefused from a node that is not
  // the fc), refusal_events (command_refused safety events published: the fc's and its own).
  const common::CounterSet& counters() const override { return counter_set_; }
  const DroneCanNode& dronecan() const { return dronecan_; }

 private:
  void on_state(const a3lcm::vehicle_state_t& state);
  void on_command(const a3lcm::fc_command_t& command);
  void on_esc(const EscRawCommand& esc);
  void on_status(const FcStatus& status);
  void on_grant(int64_t utime_us);
  void on_fc_refusal(const FcCommandRefused& report);
  // True when a transfer comes from the fc; else counts and reports it.
  bool from_fc(const ReceivedTransfer& transfer);
  void publish_safety(const a3lcm::safety_event_t& event);
  void publish_sensors(const a3lcm::vehicle_state_t& state);
  template <class Msg>
  void publish_can(const Msg& msg, uint8_t priority);
  void update_health();
  void warn(uint64_t count, const std::string& message) const;

  // The vehicle's channels, resolved once.
  struct Channels {
    common::TypedChannel<a3lcm::vehicle_state_t> state;
    common::TypedChannel<a3lcm::actuator_cmd_t> actuators;
    common::TypedChannel<a3lcm::fc_command_t> command;
    common::TypedChannel<a3lcm::fc_status_t> status;
    common::TypedChannel<a3lcm::safety_event_t> safety;
  };

  BridgeNodeConfig config_;
  Channels channels_;
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
  std::array<double, 3> last_p_W_m_{};  // where the vehicle was at the last state
  uint8_t last_foreign_source_ = 0;
  uint16_t last_foreign_type_ = 0;
  RefusalReports foreign_refusals_;

  common::CounterSet counter_set_;
  struct Counters {
    explicit Counters(common::CounterSet& s)
        : states(s.add("states")), states_rejected(s.add("states_rejected")), imu(s.add("imu")),
          gnss(s.add("gnss")), baro(s.add("baro")), mag(s.add("mag")), battery(s.add("battery")),
          esc_frames(s.add("esc_frames")), esc_rejected(s.add("esc_rejected")), esc_clamped(s.add("esc_clamped")),
          commands(s.add("commands")), commands_nonfinite(s.add("commands_nonfinite")),
          statuses(s.add("statuses")), can_publish_failures(s.add("can_publish_failures")),
          clock_grants(s.add("clock_grants")), rejected_source(s.add("rejected_source")),
          refusal_events(s.add("refusal_events")) {}
    common::Counter &states, &states_rejected, &imu, &gnss, &baro, &mag, &battery, &esc_frames, &esc_rejected,
        &esc_clamped, &commands, &commands_nonfinite, &statuses, &can_publish_failures, &clock_grants,
        &rejected_source, &refusal_events;
  } counters_{counter_set_};
};

}  // namespace a3::bridge
