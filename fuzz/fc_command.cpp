// Fuzz target "fc_command": a3.fc.Command payloads as the fc node hands them on
// (flight_command_from_can, then FlightController::on_command), each followed by control steps,
// with the vehicle at rest on the ground as its sensors report it. Below the fc node's CAN
// checks (source node, repeated seq): every payload that decodes reaches the controller.
// Input: records of a 25-byte a3.fc.Command payload and one byte, the control steps to run
// after it (5 ms each). Invariant: every rotor throttle is a number in [0, 1].
#include <cmath>

#include "bridge/dronecan/msg/a3_fc.hpp"
#include "bridge/dronecan/serialization.hpp"
#include "bridge/fc/flight_controller.hpp"
#include "bridge/nodes/fc_messages.hpp"
#include "fuzz/fuzz_target.hpp"
#include "fuzz/input_reader.hpp"

namespace {

namespace bridge = a3::bridge;

constexpr std::size_t kCommandBytes = (bridge::FcCommand::kType.max_bit_length + 7) / 8;
constexpr double kStep_s = 0.005;

// What the sensors of a level vehicle standing at the origin report.
void sense_at_rest(bridge::FlightController& fc, double t_s) {
  auto& estimator = fc.estimator();
  estimator.on_imu(t_s, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, 9.80665));
  estimator.on_gnss(t_s, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  estimator.on_baro(t_s, 0.0);
  estimator.on_magnetometer(t_s, bridge::earth_field_direction_W());
}

double run_steps(bridge::FlightController& fc, double t_s, int steps) {
  for (int i = 0; i < steps; ++i) {
    t_s += kStep_s;
    sense_at_rest(fc, t_s);
    const bridge::FcOutput out = fc.step(t_s);
    for (const double throttle : out.throttle) {
      a3::fuzz::require(throttle >= 0.0 && throttle <= 1.0, "a rotor throttle outside [0, 1] (or NaN)");
    }
  }
  return t_s;
}

}  // namespace

A3_FUZZ_TARGET(fc_command) {
  bridge::FlightController fc(bridge::FcParams{});
  double t_s = run_steps(fc, 0.0, 100);  // the estimator has attitude and position
  a3::fuzz::InputReader in(input);
  while (!in.empty()) {
    const a3::fuzz::Input payload = in.bytes(kCommandBytes);
    const int steps = in.byte();
    bridge::FcCommand command;
    if (!bridge::decode_payload(payload.data(), payload.size(), command).ok()) continue;
    (void)fc.on_command(bridge::flight_command_from_can(command), t_s);
    t_s = run_steps(fc, t_s, steps);
  }
}
