// Confidence intervals against published tables: Student's t quantiles, t-intervals of a mean,
// Wilson intervals of a rate.
#include <gtest/gtest.h>

#include <cmath>

#include "rigs/sweep/confidence.hpp"

namespace a3::rigs::sweep {
namespace {

TEST(Confidence, StudentTQuantilesMatchTheTables) {
  EXPECT_NEAR(student_t_quantile(0.975, 1), 12.7062, 1e-3);
  EXPECT_NEAR(student_t_quantile(0.975, 2), 4.3027, 1e-3);
  EXPECT_NEAR(student_t_quantile(0.975, 4), 2.7764, 1e-3);
  EXPECT_NEAR(student_t_quantile(0.975, 9), 2.2622, 1e-3);
  EXPECT_NEAR(student_t_quantile(0.975, 30), 2.0423, 1e-3);
  EXPECT_NEAR(student_t_quantile(0.975, 1000), 1.9623, 1e-3);
  EXPECT_NEAR(student_t_quantile(0.95, 5), 2.0150, 1e-3);
  EXPECT_NEAR(student_t_quantile(0.025, 4), -2.7764, 1e-3);
  EXPECT_NEAR(student_t_quantile(0.5, 3), 0.0, 1e-9);
  EXPECT_THROW(student_t_quantile(1.0, 3), std::invalid_argument);
  EXPECT_THROW(student_t_quantile(0.9, 0), std::invalid_argument);
}

TEST(Confidence, TIntervalOfAMean) {
  const auto ci = t_interval({0.2, 0.4, 0.6});
  ASSERT_TRUE(ci.has_value());
  // 0.4 ± t(0.975, 2) · 0.2 / √3
  EXPECT_NEAR(ci->lo, 0.4 - 4.30265 * 0.2 / std::sqrt(3.0), 1e-4);
  EXPECT_NEAR(ci->hi, 0.4 + 4.30265 * 0.2 / std::sqrt(3.0), 1e-4);
  const auto flat = t_interval({0.5, 0.5, 0.5, 0.5});
  ASSERT_TRUE(flat.has_value());
  EXPECT_DOUBLE_EQ(flat->lo, 0.5);
  EXPECT_DOUBLE_EQ(flat->hi, 0.5);
  EXPECT_FALSE(t_interval({0.7}).has_value());
  EXPECT_NEAR(sample_sd({1.0, 2.0, 3.0, 4.0}), std::sqrt(5.0 / 3.0), 1e-12);
}

TEST(Confidence, WilsonIntervalOfARate) {
  const Interval none = wilson_interval(0, 10);
  EXPECT_DOUBLE_EQ(none.lo, 0.0);
  EXPECT_NEAR(none.hi, 0.2775, 1e-4);
  const Interval half = wilson_interval(5, 10);
  EXPECT_NEAR(half.lo, 0.2366, 1e-4);
  EXPECT_NEAR(half.hi, 0.7634, 1e-4);
  const Interval all = wilson_interval(3, 3);
  EXPECT_NEAR(all.lo, 0.4385, 1e-4);
  EXPECT_NEAR(all.hi, 1.0, 1e-12);
  EXPECT_THROW(wilson_interval(4, 3), std::invalid_argument);
  EXPECT_THROW(wilson_interval(0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace a3::rigs::sweep
