// The fc node: a flight controller that knows its vehicle only through CAN, as a real
// autopilot on a DroneCAN bus does. It subscribes to the sensor messages (ahrs.RawIMU,
// gnss.Fix2, air_data.StaticPressure, ahrs.MagneticFieldStrength2, power.BatteryInfo) and to
// a3.fc.Command, feeds a FlightController, and publishes esc.RawCommand at the control rate
// (FcParams::control_rate_hz, ≥ 200 Hz; all zeros when disarmed), a3.fc.Status at the status
// rate and right after each command it handles, and NodeStatus at 1 Hz (health: OK; WARNING
// when a link-loss, geofence or altitude failsafe is in force or a sensor is silent; ERROR on
// low battery; CRITICAL after an emergency stop in flight. Mode INITIALIZATION until the
// estimator has attitude and position). Every command, a heartbeat too, keeps the command
// link alive; a command repeated with the same seq is not executed twice. An accepted command
// runs a control step at once (step_on_command), so its first ESC frame does not wait for the
// next tick. In lockstep its clock is the last a3.sim.Clock from the bridge (follow_sim_clock).
// Only its command sources command it: a3.fc.Command and a3.sim.Clock from any other node are
// refused, counted and reported in a3.fc.CommandRefused, at most one per report interval
// (command_sources.hpp; the threat model is in bridge/README.md).
// The estimator times IMU samples by their integration intervals, not by when their
// frames arrived. It never touches LCM: start()'s bus is not used.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "bridge/can/can_bus.hpp"
#include "bridge/dronecan/msg/a3_fc.hpp"
#include "bridge/dronecan/msg/a3_fc_refusal.hpp"
#include "bridge/dronecan/node.hpp"
#include "bridge/fc/flight_controller.hpp"
#include "bridge/fc/geo.hpp"
#include "bridge/nodes/command_sources.hpp"
#include "common/clock.hpp"
#include "common/node.hpp"

namespace a3::bridge {

struct FcNodeConfig {
  FcParams params;
  EstimatorNoise estimator_noise;
  Geodetic home = kDefaultHome;   // ENU origin; its height is the baro's reference (MSL)
  uint8_t node_id = kDefaultFcNodeId;
  // The nodes whose a3.fc.Command (and a3.sim.Clock) the fc obeys: the bridge and, where one is
  // on the bus, a ground station. Not empty, not the fc's own ID.
  std::vector<uint8_t> command_sources{kDefaultBridgeNodeId};
  int64_t refusal_report_interval_us = 1'000'000;  // at most one a3.fc.CommandRefused per interval
  bool step_on_command = true;
  int64_t sensor_timeout_us = 200'000;  // a sensor silent this long makes health WARNING
};


class FcNode final : public common::Node {
 public:
  // The CAN bus must outlive the node. Throws std::invalid_argument for a bad node ID.
  FcNode(CanBus& can, FcNodeConfig config);
  ~FcNode() override;

  std::string name() const override { return "fc"; }
  // None: a flight controller talks only CAN (its clock, in lockstep, comes as a3.sim.Clock).
  std::optional<common::NodePorts> ports() const override { return common::NodePorts(); }
  void start(common::Executor& executor, common::Bus& bus) override;
  // Stops receiving and the timers (the executor's thread, or after it stopped).
  void stop();

  // Lockstep (DESIGN.md "Time"): the node's clock stands at the last a3.sim.Clock received on
  // CAN; before start(), with the stepped clock of the executor the node runs on.
  void follow_sim_clock(common::SteppedClock* clock) { sim_clock_ = clock; }

  // steps, esc_published, status_published, commands (a3.fc.Command received, heartbeats
  // included), heartbeats, commands_refused, commands_repeated (same seq: not executed again),
  // imu, gnss, baro, mag, battery, sensor_rejected (unusable values: NaN, no fix, range),
  // clock_grants (a3.sim.Clock received), commands_rejected_source (a3.fc.Command or
  // a3.sim.Clock from a node that is not a command source), refusal_reports
  // (a3.fc.CommandRefused sent).
  const common::CounterSet& counters() const override { return counter_set_; }
  // Safe from any thread.
  FlightStatus status_snapshot() const;
  // The node's own thread only (or after it stopped).
  const FlightController& controller() const { return fc_; }
  const DroneCanNode& dronecan() const { return dronecan_; }

 private:
  void subscribe_sensors();
  void on_command(const FcCommand& command);
  // A commanding transfer from a node that is not a command source: counted, reported.
  void refuse_source(uint8_t source_node_id, uint16_t data_type_id, uint8_t command, int32_t seq);
  void report_refusals(uint64_t refused_in_report, uint64_t refused_total);
  void step();
  void publish_status();
  void update_health();
  double now_s() const;
  // The estimator's IMU time: advanced by each report's integration interval (the sensor's own
  // clock); by the difference of receive times only for a report without one.
  double imu_time_s(double rx_s, double interval_s);
  void reject(const char* what);

  FcNodeConfig config_;
  LocalFrame frame_;
  FlightController fc_;
  DroneCanNode dronecan_;
  common::Executor* executor_ = nullptr;
  std::vector<common::TimerId> timers_;
  bool have_command_seq_ = false;
  int32_t last_command_seq_ = 0;
  int64_t last_imu_us_ = -1, last_gnss_us_ = -1, last_baro_us_ = -1;
  double imu_time_s_ = -1.0, last_imu_rx_s_ = 0.0;

  common::SteppedClock* sim_clock_ = nullptr;
  FcCommandRefused last_refused_;
  RefusalReports refusals_;
  common::CounterSet counter_set_;
  struct Counters {
    explicit Counters(common::CounterSet& s)
        : steps(s.add("steps")), esc_published(s.add("esc_published")), status_published(s.add("status_published")),
          commands(s.add("commands")), heartbeats(s.add("heartbeats")), commands_refused(s.add("commands_refused")),
          commands_repeated(s.add("commands_repeated")), imu(s.add("imu")), gnss(s.add("gnss")),
          baro(s.add("baro")), mag(s.add("mag")), battery(s.add("battery")),
          sensor_rejected(s.add("sensor_rejected")), clock_grants(s.add("clock_grants")),
          commands_rejected_source(s.add("commands_rejected_source")), refusal_reports(s.add("refusal_reports")) {}
    common::Counter &steps, &esc_published, &status_published, &commands, &heartbeats, &commands_refused,
        &commands_repeated, &imu, &gnss, &baro, &mag, &battery, &sensor_rejected, &clock_grants,
        &commands_rejected_source, &refusal_reports;
  } counters_{counter_set_};
  mutable std::mutex status_mutex_;
  FlightStatus status_copy_;
};

}  // namespace a3::bridge
