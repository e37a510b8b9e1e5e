// Wall and virtual clocks.
#include "common/clock.hpp"

#include <time.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace a3::common {

int64_t WallClock::monotonic_now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

WallClock::WallClock(double real_time_factor, int64_t epoch_mono_ns)
    : real_time_factor_(real_time_factor),
      epoch_mono_ns_(epoch_mono_ns < 0 ? monotonic_now_ns() : epoch_mono_ns) {
  if (!(real_time_factor > 0.0) || !std::isfinite(real_time_factor)) {
    throw std::invalid_argument("WallClock: real-time factor must be a positive number, got " +
                                std::to_string(real_time_factor));
  }
}

int64_t WallClock::now_us() const {
  const double elapsed_ns = static_cast<double>(monotonic_now_ns() - epoch_mono_ns_);
  return static_cast<int64_t>(std::floor(elapsed_ns * real_time_factor_ * 1e-3));
}

int64_t WallClock::mono_ns_at(int64_t sim_us) const {
  return epoch_mono_ns_ +
         static_cast<int64_t>(std::ceil(static_cast<double>(sim_us) * 1e3 / real_time_factor_));
}

SteppedClock::SteppedClock(int64_t start_us)
    : granted_us_(start_us), last_grant_mono_ns_(WallClock::monotonic_now_ns()) {}

std::optional<int64_t> SteppedClock::due_mono_ns(int64_t sim_us) const {
  if (sim_us > now_us()) return std::nullopt;
  return last_grant_mono_ns();
}

int64_t SteppedClock::available_mono_ns(int64_t) const { return last_grant_mono_ns(); }

bool SteppedClock::advance_to(int64_t t_us) {
  if (t_us <= granted_us_.load(std::memory_order_relaxed)) return false;
  last_grant_mono_ns_.store(WallClock::monotonic_now_ns(), std::memory_order_release);
  granted_us_.store(t_us, std::memory_order_release);
  return true;
}

void VirtualClock::advance_to(int64_t t_us) {
  if (t_us < now_us_) {
    throw std::logic_error("VirtualClock: cannot go back from " + std::to_string(now_us_) +
                           " us to " + std::to_string(t_us) + " us");
  }
  now_us_ = t_us;
}

}  // namespace a3::common
