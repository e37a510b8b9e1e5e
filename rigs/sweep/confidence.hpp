// 95 % confidence intervals for the sweep's aggregates: Student's t-interval for a mean
// (α³, SP), the Wilson score interval for a rate (success).
#pragma once

#include <optional>
#include <vector>

namespace a3::rigs::sweep {

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

// The p-quantile of Student's t with `dof` degrees of freedom (dof >= 1, 0 < p < 1).
double student_t_quantile(double p, int dof);

double mean_of(const std::vector<double>& x);
// Sample standard deviation (n - 1); 0 for fewer than two values.
double sample_sd(const std::vector<double>& x);

// mean ± t_{(1+confidence)/2, n-1} · s / √n; none for fewer than two values.
std::optional<Interval> t_interval(const std::vector<double>& x, double confidence = 0.95);

// Wilson score interval of successes/n at the given confidence; n >= 1.
Interval wilson_interval(int successes, int n, double confidence = 0.95);

}  // namespace a3::rigs::sweep
