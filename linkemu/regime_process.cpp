// Alternating renewal process of the normal and degraded regimes.
#include "linkemu/regime_process.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "linkemu/distributions.hpp"

namespace a3::linkemu {
namespace {
constexpr int64_t kNever = std::numeric_limits<int64_t>::max();
}

RegimeProcess::RegimeProcess(common::Rng rng, const RegimeTiming& timing, StartRegime start,
                             int64_t start_us)
    : rng_(std::move(rng)), timing_(timing), episode_start_us_(start_us) {
  if (!(timing.degraded_share >= 0.0 && timing.degraded_share < 1.0)) {
    throw std::invalid_argument("degraded share must be in [0, 1), got " +
                                std::to_string(timing.degraded_share));
  }
  if (timing.degraded_share > 0.0 && (!(timing.normal_dwell_mean_s > timing.min_dwell_s) ||
                                      !(timing.degraded_dwell_mean_s > timing.min_dwell_s))) {
    throw std::invalid_argument(
        "regime dwell means (normal " + std::to_string(timing.normal_dwell_mean_s) +
        " s, degraded " + std::to_string(timing.degraded_dwell_mean_s) +
        " s) must exceed the minimum dwell " + std::to_string(timing.min_dwell_s) + " s");
  }
  switch (start) {
    case StartRegime::kStationary: degraded_ = rng_.bernoulli(timing.degraded_share); break;
    case StartRegime::kNormal: degraded_ = false; break;
    case StartRegime::kDegraded: degraded_ = true; break;
  }
  if (timing.degraded_share == 0.0 && !degraded_) {
    episode_end_us_ = kNever;
  } else {
    episode_end_us_ = start_us + draw_dwell_us(degraded_);
  }
}

int64_t RegimeProcess::draw_dwell_us(bool degraded) {
  const double mean_s = degraded ? timing_.degraded_dwell_mean_s : timing_.normal_dwell_mean_s;
  const double dwell_s = sample_shifted_exponential(rng_, timing_.min_dwell_s, mean_s);
  return std::max<int64_t>(1, std::llround(dwell_s * 1e6));
}

void RegimeProcess::advance_to(int64_t t_us) {
  while (t_us >= episode_end_us_) {
    degraded_ = !degraded_;
    episode_start_us_ = episode_end_us_;
    episode_end_us_ = (timing_.degraded_share == 0.0 && !degraded_)
                          ? kNever
                          : episode_start_us_ + draw_dwell_us(degraded_);
  }
}

}  // namespace a3::linkemu
