// The distribution families of the slice profiles, with their sampling (from a seeded
// common::Rng) and the closed forms the fit and the tests use.
#pragma once

#include "common/rng.hpp"

namespace a3::linkemu {

// Latency of one slice: lognormal in the normal regime, the same lognormal scaled by
// degraded_factor in the degraded regime. Over time (degraded a share w of the time) the
// latency is the mixture (1 - w)·LN(ln m, σ) + w·LN(ln(m·k), σ).
struct LatencyMixture {
  double normal_median_ms = 1.0;  // m
  double sigma = 0.1;             // σ of ln(latency)
  double degraded_factor = 1.0;   // k >= 1

  double sample_ms(common::Rng& rng, bool degraded) const;
  // Of the mixture with degraded share w.
  double cdf(double lat_ms, double degraded_share) const;
  double mean_ms(double degraded_share) const;
  double quantile_ms(double p, double degraded_share) const;
};

// Lognormal with the given mean and coefficient of variation (sd / mean).
double sample_lognormal_mean_cv(common::Rng& rng, double mean, double cv);
// Gamma(shape, scale 1), Marsaglia–Tsang.
double sample_gamma(common::Rng& rng, double shape);
// Beta with the given mean in (0, 1) and concentration α + β.
double sample_beta_mean(common::Rng& rng, double mean, double concentration);
// min + Exp(mean - min): a dwell time of at least min with the given mean.
double sample_shifted_exponential(common::Rng& rng, double min, double mean);

// Standard normal CDF.
double standard_normal_cdf(double z);

}  // namespace a3::linkemu
