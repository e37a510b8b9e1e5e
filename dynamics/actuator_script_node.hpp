// A node that plays a scripted sequence of rotor commands on A3_ACTUATORS (actuator_cmd_t):
// throttles as a function of time, published on a grid of whole periods plus an offset, from
// start_s to end_s. For open-loop tests, benchmarks and demonstrations of the dynamics node.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>

#include "common/channels.hpp"
#include "common/node.hpp"

namespace a3::dynamics {

struct ActuatorScript {
  std::function<std::array<double, 4>(double t_s)> throttle;
  double rate_hz = 100.0;
  double offset_s = 0.005;  // between the dynamics steps, so each command lands in one step
  double start_s = 0.0;
  double end_s = 1e300;
  common::VehicleId vehicle = 0;  // commands on this vehicle's A3_ACTUATORS
};

class ActuatorScriptNode final : public common::Node {
 public:
  using ThrottleFn = std::function<std::array<double, 4>(double t_s)>;
  explicit ActuatorScriptNode(ActuatorScript script);
  // The defaults of ActuatorScript with this throttle function.
  explicit ActuatorScriptNode(ThrottleFn throttle) : ActuatorScriptNode(with_throttle(std::move(throttle))) {}
  std::string name() const override { return "actuator_script"; }
  void start(common::Executor& executor, common::Bus& bus) override;
  std::optional<common::NodePorts> ports() const override {
    return common::NodePorts().publishes(common::channels::kActuators.of(script_.vehicle));
  }
  uint64_t published() const { return published_; }

 private:
  void publish();
  static ActuatorScript with_throttle(ThrottleFn throttle) {
    ActuatorScript script;
    script.throttle = std::move(throttle);
    return script;
  }

  ActuatorScript script_;
  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  common::TimerId timer_ = 0;
  int64_t period_us_ = 10000;
  int64_t next_us_ = 0;
  uint64_t published_ = 0;
};

}  // namespace a3::dynamics
