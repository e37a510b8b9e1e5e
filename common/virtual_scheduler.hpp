// Discrete-event scheduler for the virtual-time runtime: every registered node's timers
// and bus deliveries run in one thread, in (time, insertion) order, as fast as possible.
// Deterministic: the same inputs give the same order of events.
#pragma once

#include <cstdint>

#include "common/clock.hpp"
#include "common/executor.hpp"
#include "common/timer_queue.hpp"

namespace a3::common {

class VirtualScheduler final : public Executor {
 public:
  explicit VirtualScheduler(int64_t start_us = 0) : clock_(start_us) {}

  const Clock& clock() const override { return clock_; }
  TimerId schedule(int64_t first_us, int64_t period_us, std::function<void()> fn) override;
  void cancel(TimerId id) override { queue_.cancel(id); }

  // Runs every event due at or before end_us, then sets the clock to end_us.
  // Returns the number of events run.
  uint64_t run_until(int64_t end_us);
  // Runs the single next event, if any; returns false when the queue is empty.
  bool step();
  // Ends run_until early (from inside a callback); the clock stays at the event's time.
  void request_stop() { stop_requested_ = true; }
  bool stop_requested() const { return stop_requested_; }
  uint64_t events_run() const { return events_run_; }
  std::size_t pending() const { return queue_.size(); }

 private:
  void run_event(TimerQueue::Due& due);

  VirtualClock clock_;
  TimerQueue queue_;
  uint64_t events_run_ = 0;
  bool stop_requested_ = false;
};

}  // namespace a3::common
