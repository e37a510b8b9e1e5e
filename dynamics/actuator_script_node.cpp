// Scripted rotor commands.
#include "dynamics/actuator_script_node.hpp"

#include <cmath>
#include <stdexcept>

#include "a3lcm/actuator_cmd_t.hpp"
#include "common/channels.hpp"

namespace a3::dynamics {

ActuatorScriptNode::ActuatorScriptNode(ActuatorScript script) : script_(std::move(script)) {
  if (!script_.throttle) throw std::invalid_argument("actuator script: no throttle function");
  if (!(script_.rate_hz > 0.0)) throw std::invalid_argument("actuator script: rate must be > 0 Hz");
}

void ActuatorScriptNode::start(common::Executor& executor, common::Bus& bus) {
  executor_ = &executor;
  bus_ = &bus;
  const auto period_us = static_cast<int64_t>(std::llround(1e6 / script_.rate_hz));
  const auto offset_us = static_cast<int64_t>(std::llround(script_.offset_s * 1e6));
  const int64_t from_us = std::max(executor.clock().now_us(), static_cast<int64_t>(script_.start_s * 1e6));
  const int64_t k = (from_us - offset_us + period_us - 1) / period_us;
  period_us_ = period_us;
  next_us_ = k * period_us + offset_us;
  timer_ = executor.schedule(next_us_, period_us, [this] { publish(); });
}

void ActuatorScriptNode::publish() {
  // The grid time, not the (possibly late) clock: the same commands in both runtimes.
  const int64_t now_us = next_us_;
  next_us_ += period_us_;
  const double t_s = now_us * 1e-6;
  if (t_s > script_.end_s) {
    executor_->cancel(timer_);
    return;
  }
  a3lcm::actuator_cmd_t cmd;
  cmd.utime_us = now_us;
  const auto throttle = script_.throttle(t_s);
  for (int i = 0; i < 4; ++i) cmd.throttle[i] = throttle[i];
  cmd.armed = true;
  bus_->publish(common::channels::kActuators.of(script_.vehicle), cmd);
  ++published_;
}

}  // namespace a3::dynamics
