// A lockstep follower's answers.
#include "common/grant_acknowledger.hpp"

#include <utility>

#include "a3lcm/clock_ack_t.hpp"
#include "common/channels.hpp"

namespace a3::common {

GrantAcknowledger::GrantAcknowledger(const SteppedClock& clock, const LcmBus& node_bus, Bus& answers, std::string node)
    : clock_(clock), node_bus_(node_bus), answers_(answers), node_(std::move(node)) {}

void GrantAcknowledger::after_due_timers() {
  if (!answer_due_) return;
  answer_due_ = false;
  a3lcm::clock_ack_t ack;
  ack.utime_us = clock_.now_us();
  ack.round = round_;
  ack.messages_published = static_cast<int64_t>(node_bus_.messages_published());
  ack.node = node_;
  answers_.publish(channels::kClockAck, ack);
}

}  // namespace a3::common
