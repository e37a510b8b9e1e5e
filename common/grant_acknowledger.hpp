// A lockstep follower's answer to the time master (DESIGN.md "Time"): once the timers due at a
// grant it heard have run, and with them everything they published, it publishes
// clock_ack_t{utime_us and round of the grant, the messages its node's bus has published,
// node} on A3_CLOCK_ACK, on a bus of its own (answers_lcm_url: only the master listens there).
// Every grant heard is answered, a repeated one too, so that one lost datagram cannot stall the
// loop. The follower's executor calls it from its own thread (ClockDriver); it never moves the
// clock.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "common/clock.hpp"
#include "common/clock_driver.hpp"
#include "common/lcm_bus.hpp"

namespace a3::common {

class GrantAcknowledger final : public ClockDriver {
 public:
  // All three must outlive the acknowledger: the node's bus (whose publications are counted)
  // and the bus the answers go out on.
  GrantAcknowledger(const SteppedClock& clock, const LcmBus& node_bus, Bus& answers, std::string node);

  // A grant arrived (a bus callback on the same thread).
  void grant_heard(int32_t round) {
    round_ = round;
    answer_due_ = true;
  }
  bool poll(int64_t) override { return false; }
  void after_due_timers() override;
  std::optional<int64_t> next_poll_mono_ns() const override { return std::nullopt; }

 private:
  const SteppedClock& clock_;
  const LcmBus& node_bus_;
  Bus& answers_;
  std::string node_;
  bool answer_due_ = false;
  int32_t round_ = 0;
};

}  // namespace a3::common
