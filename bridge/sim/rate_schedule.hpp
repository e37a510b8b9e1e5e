// When a sensor driven by incoming samples reports: on a schedule of whole periods (a 200 Hz
// IMU: every 5 ms), each report taking the freshest sample at or after its tick. So the rate is
// min(schedule, sample rate): with states at 250 Hz a 200 Hz sensor reports on 4 states of 5;
// at 200 Hz, on every one; at 100 Hz, on every one (100 Hz: no sample is ever repeated). A
// sample up to 250 us (at most a tenth of a period) short of a tick counts as on it, for
// timestamps that jitter around the grid.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace a3::bridge {

class RateSchedule {
 public:
  explicit RateSchedule(double rate_hz) {
    if (!(rate_hz > 0.0 && rate_hz <= 10000.0)) {
      throw std::invalid_argument("sensor rate must be in (0, 10000] Hz, got " + std::to_string(rate_hz));
    }
    period_us_ = std::llround(1e6 / rate_hz);
    tolerance_us_ = std::min<int64_t>(period_us_ / 10, 250);
  }

  // True when a sample at t_us is due for a report (and moves to the next tick).
  bool due(int64_t t_us) {
    if (started_ && t_us < last_us_) started_ = false;  // time went back: start over
    if (started_ && t_us < next_us_ - tolerance_us_) return false;  // between ticks
    next_us_ = started_ ? next_us_ + period_us_ : t_us + period_us_;
    if (next_us_ <= t_us) next_us_ = t_us + period_us_;  // samples stopped for a while: skip ticks
    started_ = true;
    last_us_ = t_us;
    return true;
  }
  void reset() { started_ = false; }
  int64_t period_us() const { return period_us_; }

 private:
  int64_t period_us_ = 0;
  int64_t tolerance_us_ = 0;
  int64_t next_us_ = 0;
  int64_t last_us_ = 0;  // the last sample reported
  bool started_ = false;
};

}  // namespace a3::bridge
