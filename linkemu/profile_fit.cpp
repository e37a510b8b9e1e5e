// Nested bisection for the latency mixture; mean balance for the other terms.
#include "linkemu/profile_fit.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace a3::linkemu {
namespace {

// Bisection for an increasing f: the x in [lo, hi] with f(x) = target.
template <typename F>
double solve_increasing(F f, double target, double lo, double hi, int iterations = 80) {
  for (int i = 0; i < iterations; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Normal mean such that (1 - w)·normal + w·degraded = target.
double balance_mean(double target, double degraded_mean, double w, const char* what) {
  const double normal = (target - w * degraded_mean) / (1.0 - w);
  if (!(normal > 0.0)) {
    std::ostringstream message;
    message << what << ": degraded mean " << degraded_mean << " with share " << w
            << " leaves no room for the target mean " << target;
    throw std::invalid_argument(message.str());
  }
  return normal;
}

}  // namespace

LatencyMixture fit_latency_mixture(double mean_ms, double median_ms, double p90_ms, double w) {
  if (!(median_ms > 0.0 && median_ms < p90_ms && mean_ms > 0.0) || !(w >= 0.0 && w < 1.0)) {
    throw std::invalid_argument("fit_latency_mixture: needs 0 < median < p90, mean > 0, 0 <= w < 1");
  }
  LatencyMixture m;
  // For given σ and k: the median m that puts the mixture median on target.
  auto fit_median = [&](double sigma, double k) {
    m.sigma = sigma;
    m.degraded_factor = k;
    const double ln_m = solve_increasing(
        [&](double x) {
          m.normal_median_ms = std::exp(x);
          return -m.cdf(median_ms, w);  // the CDF at the target falls as m grows
        },
        -0.5, std::log(median_ms) - std::log(k) - 10.0 * sigma, std::log(median_ms) + 10.0 * sigma);
    m.normal_median_ms = std::exp(ln_m);
  };
  // For given k: σ (and m) that put the P90 on target.
  auto fit_sigma = [&](double k) {
    const double sigma = solve_increasing(
        [&](double s) {
          fit_median(s, k);
          return m.quantile_ms(0.9, w);
        },
        p90_ms, 1e-4, 4.0, 60);
    fit_median(sigma, k);
  };
  if (w == 0.0) {
    fit_sigma(1.0);
  } else {
    const double ln_k = solve_increasing(
        [&](double x) {
          fit_sigma(std::exp(x));
          return m.mean_ms(w);
        },
        mean_ms, 0.0, std::log(1000.0), 60);
    fit_sigma(std::exp(ln_k));
  }
  const double tolerance = 1e-6;
  const auto off = [&](double got, double want) { return std::abs(got / want - 1.0) > tolerance; };
  if (off(m.quantile_ms(0.5, w), median_ms) || off(m.quantile_ms(0.9, w), p90_ms) ||
      (w > 0.0 && off(m.mean_ms(w), mean_ms))) {
    std::ostringstream message;
    message << "no lognormal scaled mixture with degraded share " << w << " has mean " << mean_ms
            << ", median " << median_ms << " and P90 " << p90_ms << " (closest: mean "
            << m.mean_ms(w) << ", median " << m.quantile_ms(0.5, w) << ", P90 "
            << m.quantile_ms(0.9, w) << ")";
    throw std::invalid_argument(message.str());
  }
  return m;
}

SliceProfile fit_slice_profile(const SliceProfile& design) {
  SliceProfile p = design;
  const CorpusTargets& t = design.targets;
  const double w = design.degraded_share;
  const std::string name = to_string(design.slice);
  try {
    p.lat_ms = fit_latency_mixture(t.lat_mean_ms, t.lat_median_ms, t.lat_p90_ms, w);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(name + " lat_ms: " + e.what());
  }
  // jitter = ratio · lat · noise(mean 1), noise independent of lat: E[jitter] = ratio · E[lat].
  p.jitter_ms.ratio_to_lat = t.jitter_mean_ms / t.lat_mean_ms;
  p.loss_pct.normal_mean =
      balance_mean(t.loss_mean_pct, design.loss_pct.degraded_mean, w, (name + " loss_pct").c_str());
  p.throughput_mbps.normal_mean = balance_mean(
      t.throughput_mean_mbps, design.throughput_mbps.degraded_mean, w, (name + " throughput_mbps").c_str());
  p.edge_load.normal_mean = balance_mean(t.edge_load_mean, design.edge_load.degraded_mean, w,
                                         (name + " edge_load").c_str());
  if (!(p.edge_load.normal_mean < 1.0)) {
    throw std::invalid_argument(name + " edge_load: the normal-regime mean would be >= 1");
  }
  return p;
}

SliceProfiles fit_slice_profiles(const SliceProfiles& design) {
  SliceProfiles fitted = design;
  for (SliceProfile& p : fitted.slices) p = fit_slice_profile(p);
  return fitted;
}

}  // namespace a3::linkemu
