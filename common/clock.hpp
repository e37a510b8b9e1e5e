// Time for every node: the Clock interface, a wall clock scaled by a real-time factor,
// and a virtual clock advanced by the discrete-event scheduler (DESIGN.md "Time").
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>

namespace a3::common {

class Clock {
 public:
  virtual ~Clock() = default;
  // Simulated time since the start of the run.
  virtual int64_t now_us() const = 0;
  double now_s() const { return static_cast<double>(now_us()) * 1e-6; }
};

// A clock a real-time executor can wait on: it says when (CLOCK_MONOTONIC) a simulated
// instant is reached, or that it is not known yet (lockstep: not granted so far).
class RealTimeClock : public Clock {
 public:
  // The CLOCK_MONOTONIC instant (ns) at which simulated time reaches sim_us; nullopt while
  // that depends on something that has not happened yet (a SteppedClock's next grant).
  virtual std::optional<int64_t> due_mono_ns(int64_t sim_us) const = 0;
  // When sim_us became available (ns), for lateness: a wall clock's schedule; a stepped
  // clock's last grant (sim_us must be <= now_us()).
  virtual int64_t available_mono_ns(int64_t sim_us) const = 0;
};

// Monotonic wall clock: simulated time = (CLOCK_MONOTONIC - epoch) * real_time_factor.
// Clocks built with the same epoch agree across threads and processes on one host.
class WallClock final : public RealTimeClock {
 public:
  // epoch_mono_ns < 0: start now.
  explicit WallClock(double real_time_factor = 1.0, int64_t epoch_mono_ns = -1);

  int64_t now_us() const override;
  double real_time_factor() const { return real_time_factor_; }
  int64_t epoch_mono_ns() const { return epoch_mono_ns_; }
  // The CLOCK_MONOTONIC instant (ns) at which simulated time reaches sim_us.
  int64_t mono_ns_at(int64_t sim_us) const;
  std::optional<int64_t> due_mono_ns(int64_t sim_us) const override { return mono_ns_at(sim_us); }
  int64_t available_mono_ns(int64_t sim_us) const override { return mono_ns_at(sim_us); }

  static int64_t monotonic_now_ns();

 private:
  double real_time_factor_;
  int64_t epoch_mono_ns_;
};

// Lockstep clock (DESIGN.md "Time"): simulated time is what a time master has granted so far
// (the LockstepPacer of the vehicle's loop, A3_CLOCK grants over LCM, a3.sim.Clock frames on
// CAN); it stands still between grants, however much wall time passes. advance_to() is called
// from the thread of the executor that runs on this clock (a bus or CAN callback, the pacer);
// now_us() may be read from any thread.
class SteppedClock final : public RealTimeClock {
 public:
  explicit SteppedClock(int64_t start_us = 0);
  int64_t now_us() const override { return granted_us_.load(std::memory_order_acquire); }
  std::optional<int64_t> due_mono_ns(int64_t sim_us) const override;
  int64_t available_mono_ns(int64_t sim_us) const override;
  // Moves to t_us (a grant); an older or equal time is ignored (repeated grants). Returns
  // whether time moved.
  bool advance_to(int64_t t_us);
  // Wall time (CLOCK_MONOTONIC ns) of the last grant that moved the clock.
  int64_t last_grant_mono_ns() const { return last_grant_mono_ns_.load(std::memory_order_acquire); }

 private:
  std::atomic<int64_t> granted_us_;
  std::atomic<int64_t> last_grant_mono_ns_;
};

// Virtual clock: time moves only when the scheduler advances it; never backwards.
class VirtualClock final : public Clock {
 public:
  explicit VirtualClock(int64_t start_us = 0) : now_us_(start_us) {}
  int64_t now_us() const override { return now_us_; }
  // Throws std::logic_error when asked to go backwards.
  void advance_to(int64_t t_us);

 private:
  int64_t now_us_;
};

}  // namespace a3::common
