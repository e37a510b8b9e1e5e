// The normal/degraded regime of one slice over time: an alternating renewal process whose
// episodes last min_dwell + an exponential time, with means chosen so that the long-run
// share of degraded time is the profile's degraded_share. Degradations therefore come in
// episodes (at least min_dwell long), not as single samples.
#pragma once

#include <cstdint>

#include "common/rng.hpp"

namespace a3::linkemu {

enum class StartRegime { kStationary, kNormal, kDegraded };

struct RegimeTiming {
  double degraded_share = 0.0;
  double normal_dwell_mean_s = 1.0;
  double degraded_dwell_mean_s = 1.0;
  double min_dwell_s = 0.0;
};

class RegimeProcess {
 public:
  // Throws std::invalid_argument when a dwell mean does not exceed the minimum.
  RegimeProcess(common::Rng rng, const RegimeTiming& timing, StartRegime start, int64_t start_us);

  // Moves to t_us (never backwards: an earlier t_us is treated as the current time).
  void advance_to(int64_t t_us);
  bool degraded() const { return degraded_; }
  // End of the current episode (INT64_MAX when the regime never changes).
  int64_t episode_end_us() const { return episode_end_us_; }
  // Start of the current episode.
  int64_t episode_start_us() const { return episode_start_us_; }

 private:
  int64_t draw_dwell_us(bool degraded);

  common::Rng rng_;
  RegimeTiming timing_;
  bool degraded_ = false;
  int64_t episode_start_us_ = 0;
  int64_t episode_end_us_ = 0;
};

}  // namespace a3::linkemu
