// Student's t quantile from the regularised incomplete beta function (continued fraction,
// Lentz's method) inverted by bisection; the normal quantile by bisection on erfc.
#include "rigs/sweep/confidence.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

namespace a3::rigs::sweep {
namespace {

// Continued fraction of the incomplete beta function (Numerical Recipes' betacf).
double beta_continued_fraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  constexpr double kEpsilon = 1e-15;
  const double qab = a + b, qap = a + 1.0, qam = a - 1.0;
  double c = 1.0;
  double d = 1.0 - qab * x / qap;
  if (std::fabs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 1000; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < kEpsilon) break;
  }
  return h;
}

// I_x(a, b).
double regularized_incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double log_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  const double front = std::exp(log_front);
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_continued_fraction(a, b, x) / a;
  return 1.0 - front * beta_continued_fraction(b, a, 1.0 - x) / b;
}

double student_t_cdf(double t, int dof) {
  const double v = dof;
  const double tail = 0.5 * regularized_incomplete_beta(v / 2.0, 0.5, v / (v + t * t));
  return t >= 0.0 ? 1.0 - tail : tail;
}

double normal_quantile(double p) {
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void require_confidence(double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw std::invalid_argument("confidence " + std::to_string(confidence) + " is not in (0, 1)");
  }
}

}  // namespace

double student_t_quantile(double p, int dof) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("t quantile: p = " + std::to_string(p) + " is not in (0, 1)");
  if (dof < 1) throw std::invalid_argument("t quantile: " + std::to_string(dof) + " degrees of freedom (need >= 1)");
  if (p < 0.5) return -student_t_quantile(1.0 - p, dof);
  // The quantile lies below the Cauchy's (dof 1, the heaviest tail) for p >= 0.5.
  double lo = 0.0, hi = std::tan(std::numbers::pi * (p - 0.5)) + 1.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (student_t_cdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double mean_of(const std::vector<double>& x) {
  if (x.empty()) return 0.0;
  return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
}

double sample_sd(const std::vector<double>& x) {
  if (x.size() < 2) return 0.0;
  const double m = mean_of(x);
  double sum_sq = 0.0;
  for (const double v : x) sum_sq += (v - m) * (v - m);
  return std::sqrt(sum_sq / static_cast<double>(x.size() - 1));
}

std::optional<Interval> t_interval(const std::vector<double>& x, double confidence) {
  require_confidence(confidence);
  if (x.size() < 2) return std::nullopt;
  const double n = static_cast<double>(x.size());
  const double half = student_t_quantile(0.5 + confidence / 2.0, static_cast<int>(x.size()) - 1) * sample_sd(x) / std::sqrt(n);
  const double m = mean_of(x);
  return Interval{m - half, m + half};
}

Interval wilson_interval(int successes, int n, double confidence) {
  require_confidence(confidence);
  if (n < 1 || successes < 0 || successes > n) {
    throw std::invalid_argument("Wilson interval: " + std::to_string(successes) + " successes of " + std::to_string(n) +
                                " (need n >= 1 and 0 <= successes <= n)");
  }
  const double z = normal_quantile(0.5 + confidence / 2.0);
  const double nn = n, p = successes / nn, z2 = z * z;
  const double centre = (p + z2 / (2.0 * nn)) / (1.0 + z2 / nn);
  const double half = z / (1.0 + z2 / nn) * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace a3::rigs::sweep
