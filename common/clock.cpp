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

void VirtualClock::advance_to(int64_t t_us) {
  if (t_us < now_us_) {
    throw std::logic_error("VirtualClock: cannot go back from " + std::to_string(now_us_) +
                           " us to " + std::to_string(t_us) + " us");
  }
  now_us_ = t_us;
}

}  // namespace a3::common
