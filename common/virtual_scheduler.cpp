// Discrete-event scheduler.
#include "common/virtual_scheduler.hpp"

#include <stdexcept>
#include <string>

namespace a3::common {

TimerId VirtualScheduler::schedule(int64_t first_us, int64_t period_us,
                                   std::function<void()> fn) {
  if (period_us < 0) {
    throw std::invalid_argument("VirtualScheduler: negative period " + std::to_string(period_us));
  }
  // An event in the past runs now: virtual time never goes backwards.
  return queue_.add(first_us < clock_.now_us() ? clock_.now_us() : first_us, period_us,
                    std::move(fn));
}

void VirtualScheduler::run_event(TimerQueue::Due& due) {
  clock_.advance_to(due.time_us);
  ++events_run_;
  try {
    due.fn();
  } catch (...) {
    queue_.finish(due);  // a periodic timer keeps its callback for whoever catches this
    throw;
  }
  queue_.finish(due);
}

uint64_t VirtualScheduler::run_until(int64_t end_us) {
  stop_requested_ = false;
  const uint64_t before = events_run_;
  TimerQueue::Due due;  // reused: its callable is swapped in and out of the timer's slot
  while (!stop_requested_ && queue_.pop_due(end_us, due)) run_event(due);
  if (!stop_requested_ && end_us > clock_.now_us()) clock_.advance_to(end_us);
  return events_run_ - before;
}

bool VirtualScheduler::step() {
  const auto next = queue_.next_time_us();
  if (!next) return false;
  auto due = queue_.pop_due(*next);
  run_event(*due);
  return true;
}

}  // namespace a3::common
