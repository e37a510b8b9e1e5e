// The Executor: where a node's timers and message callbacks run. Two implementations,
// one per runtime: VirtualScheduler (discrete-event, virtual time) and RealTimeExecutor
// (one thread paced on the wall clock). Nodes only ever see this interface.
#pragma once

#include <cstdint>
#include <functional>

#include "common/clock.hpp"

namespace a3::common {

using TimerId = uint64_t;

class Executor {
 public:
  virtual ~Executor() = default;
  virtual const Clock& clock() const = 0;

  // Runs fn at first_us, then every period_us after it (period_us == 0: once).
  // Periodic timers keep their schedule (first + k·period), they do not drift.
  virtual TimerId schedule(int64_t first_us, int64_t period_us, std::function<void()> fn) = 0;
  // Cancels a timer; unknown or finished ids are ignored.
  virtual void cancel(TimerId id) = 0;

  TimerId schedule_at(int64_t t_us, std::function<void()> fn) {
    return schedule(t_us, 0, std::move(fn));
  }
  TimerId schedule_after(int64_t delay_us, std::function<void()> fn) {
    return schedule(clock().now_us() + delay_us, 0, std::move(fn));
  }
  TimerId schedule_every(int64_t period_us, std::function<void()> fn) {
    return schedule(clock().now_us() + period_us, period_us, std::move(fn));
  }
};

}  // namespace a3::common
