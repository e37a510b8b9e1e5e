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
// next tick. The estimator times IMU samples by their integration intervals, not by when their
// frames arrived. It never touches LCM: start()'s bus is not used.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "bridge/can/can_bus.hpp"
#include "bridge/dronecan/msg/a3_fc.hpp"
#include "bridge/dronecan/node.hpp"
#include "bridge/fc/flight_controller.hpp"
#include "bridge/fc/geo.hpp"
#include "common/node.hpp"

namespace a3::bridge {

struct FcNodeConfig {
  FcParams params;
  EstimatorNoise estimator_noise;
  Geodetic home = kDefaultHome;   // ENU origin; its height is the baro's reference (MSL)
  uint8_t node_id = 10;
  bool step_on_command = true;
  int64_t sensor_timeout_us = 200'000;  // a sensor silent this long makes health WARNING
};

struct FcNodeCounters {
  uint64_t steps = 0;
  uint64_t esc_published = 0;
  uint64_t status_published = 0;
  uint64_t commands = 0;          // a3.fc.Command received (heartbeats included)
  uint64_t heartbeats = 0;
  uint64_t commands_refused = 0;
  uint64_t commands_repeated = 0;  // same seq as the last one: not executed again
  uint64_t imu = 0, gnss = 0, baro = 0, mag = 0, battery = 0;
  uint64_t sensor_rejected = 0;   // sensor messages with unusable values (NaN, no fix, range)
};

class FcNode final : public common::Node {
 public:
  // The CAN bus must outlive the node. Throws std::invalid_argument for a bad node ID.
  FcNode(CanBus& can, FcNodeConfig config);
  ~FcNode() override;

  std::string name() const override { return "fc"; }
  void start(common::Executor& executor, common::Bus& bus) override;
  // Stops receiving and the timers (the executor's thread, or after it stopped).
  void stop();

  // Safe from any thread.
  FcNodeCounters counters() const;
  FlightStatus status_snapshot() const;
  // The node's own thread only (or after it stopped).
  const FlightController& controller() const { return fc_; }
  const DroneCanNode& dronecan() const { return dronecan_; }

 private:
  void subscribe_sensors();
  void on_command(const FcCommand& command);
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

  struct AtomicCounters {
    std::atomic<uint64_t> steps{0}, esc_published{0}, status_published{0}, commands{0}, heartbeats{0},
        commands_refused{0}, commands_repeated{0}, imu{0}, gnss{0}, baro{0}, mag{0}, battery{0},
        sensor_rejected{0};
  } counters_;
  mutable std::mutex status_mutex_;
  FlightStatus status_copy_;
};

}  // namespace a3::bridge
