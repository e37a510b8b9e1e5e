// Time for every node: the Clock interface, a wall clock scaled by a real-time factor,
// and a virtual clock advanced by the discrete-event scheduler (DESIGN.md "Time").
#pragma once

#include <cstdint>

namespace a3::common {

class Clock {
 public:
  virtual ~Clock() = default;
  // Simulated time since the start of the run.
  virtual int64_t now_us() const = 0;
  double now_s() const { return static_cast<double>(now_us()) * 1e-6; }
};

// Monotonic wall clock: simulated time = (CLOCK_MONOTONIC - epoch) * real_time_factor.
// Clocks built with the same epoch agree across threads and processes on one host.
class WallClock final : public Clock {
 public:
  // epoch_mono_ns < 0: start now.
  explicit WallClock(double real_time_factor = 1.0, int64_t epoch_mono_ns = -1);

  int64_t now_us() const override;
  double real_time_factor() const { return real_time_factor_; }
  int64_t epoch_mono_ns() const { return epoch_mono_ns_; }
  // The CLOCK_MONOTONIC instant (ns) at which simulated time reaches sim_us.
  int64_t mono_ns_at(int64_t sim_us) const;

  static int64_t monotonic_now_ns();

 private:
  double real_time_factor_;
  int64_t epoch_mono_ns_;
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
