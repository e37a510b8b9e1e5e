// A ClockDriver moves a real-time executor's clock itself instead of following the wall
// clock or a time master: the LockstepPacer of the vehicle's loop is one. The executor calls
// it from its own thread: poll() after waiting (it may advance the clock), after_due_timers()
// once every timer due at the current time has run, next_poll_mono_ns() to know how long it
// may wait.
#pragma once

#include <cstdint>
#include <optional>

namespace a3::common {

class ClockDriver {
 public:
  virtual ~ClockDriver() = default;
  // May advance the clock; returns whether it did.
  virtual bool poll(int64_t mono_now_ns) = 0;
  // Everything due at the clock's current time has run.
  virtual void after_due_timers() = 0;
  // CLOCK_MONOTONIC instant (ns) at which poll() should run again; nullopt: only when a
  // message (or a wake-up) comes.
  virtual std::optional<int64_t> next_poll_mono_ns() const = 0;
};

}  // namespace a3::common
