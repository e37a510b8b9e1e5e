// A lockstep follower's answers.
#include "common/grant_acknowledger.hpp"

#include <utility>

#include "a3lcm/clock_ack_t.hpp"
#include "common/channels.hpp"

namespace a3::common {

GrantAcknowledger::GrantAcknowledger(const SteppedClock& clock, LcmBus& bus, std::string node)
    : clock_(clock), bus_(bus), node_(std::move(node)) {}

void GrantAcknowledger::after_due_timers() {
  if (!answer_due_) return;
  answer_due_ = false;
  a3lcm::clock_ack_t ack;
  ack.utime_us = clock_.now_us();
  ack.round = round_;
  ack.messages_published = static_cast<int64_t>(bus_.messages_published() - answers_sent_);
  ack.node = node_;
  ++answers_sent_;
  bus_.publish(channels::kClockAck, ack);
}

}  // namespace a3::common
