// Sampling and closed forms of the slice-profile distributions.
#include "linkemu/distributions.hpp"

#include <cmath>
#include <stdexcept>

namespace a3::linkemu {

double standard_normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

double LatencyMixture::sample_ms(common::Rng& rng, bool degraded) const {
  const double median = degraded ? normal_median_ms * degraded_factor : normal_median_ms;
  return median * std::exp(sigma * rng.normal());
}

double LatencyMixture::cdf(double lat_ms, double w) const {
  if (lat_ms <= 0.0) return 0.0;
  const double z = std::log(lat_ms / normal_median_ms) / sigma;
  const double z_degraded = (std::log(lat_ms / normal_median_ms) - std::log(degraded_factor)) / sigma;
  return (1.0 - w) * standard_normal_cdf(z) + w * standard_normal_cdf(z_degraded);
}

double LatencyMixture::mean_ms(double w) const {
  return (1.0 - w + w * degraded_factor) * normal_median_ms * std::exp(0.5 * sigma * sigma);
}

double LatencyMixture::quantile_ms(double p, double w) const {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("quantile_ms: p must be in (0, 1)");
  // Bisection on ln(latency): the CDF is increasing.
  double lo = std::log(normal_median_ms) - 12.0 * sigma;
  double hi = std::log(normal_median_ms * degraded_factor) + 12.0 * sigma;
  for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
    const double mid = 0.5 * (lo + hi);
    (cdf(std::exp(mid), w) < p ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

double sample_lognormal_mean_cv(common::Rng& rng, double mean, double cv) {
  if (cv <= 0.0) return mean;
  const double s2 = std::log1p(cv * cv);
  return mean * std::exp(std::sqrt(s2) * rng.normal() - 0.5 * s2);
}

double sample_gamma(common::Rng& rng, double shape) {
  if (shape < 1.0) {
    // Gamma(a) = Gamma(a + 1) · U^(1/a).
    const double u = 1.0 - rng.uniform01();  // (0, 1]
    return sample_gamma(rng, shape + 1.0) * std::pow(u, 1.0 / shape);
  }
  const double d = shape - 1.0 / 3.0;
  const double c = 1.0 / std::sqrt(9.0 * d);
  for (;;) {
    double x, v;
    do {
      x = rng.normal();
      v = 1.0 + c * x;
    } while (v <= 0.0);
    v = v * v * v;
    const double u = rng.uniform01();
    if (u < 1.0 - 0.0331 * x * x * x * x) return d * v;
    if (u > 0.0 && std::log(u) < 0.5 * x * x + d * (1.0 - v + std::log(v))) return d * v;
  }
}

double sample_beta_mean(common::Rng& rng, double mean, double concentration) {
  const double a = sample_gamma(rng, mean * concentration);
  const double b = sample_gamma(rng, (1.0 - mean) * concentration);
  return a / (a + b);
}

double sample_shifted_exponential(common::Rng& rng, double min, double mean) {
  return min + rng.exponential(mean - min);
}

}  // namespace a3::linkemu
