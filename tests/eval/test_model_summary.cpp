// Model-level aggregation (SPEC §3) from known episode scores, failures and attempts.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/corpus_scorer.hpp"
#include "eval/model_summary.hpp"

namespace a3::eval {
namespace {

EpisodeFacts facts(bool success, double gen_time_s, double tokens, int64_t attempts) {
  EpisodeFacts f;
  f.success = success;
  f.gen_time_s = gen_time_s;
  f.total_tokens = tokens;
  f.attempts_used = attempts;
  return f;
}

Pillars pillars(double alpha3, double sp) {
  Pillars p;
  p.alpha3 = alpha3;
  p.to = 1.0;
  p.sp = sp;
  p.tc = 1.0;
  p.iq = 0.9;
  p.nr = 0.8;
  p.cc = 0.7;
  return p;
}

TEST(ModelAccumulator, MeansRatesAndPopulationInterval) {
  ModelAccumulator acc("prov/model", "uav");
  acc.add_valid(facts(true, 10.0, 4000, 1), pillars(0.9, 1.0));
  acc.add_valid(facts(false, 20.0, 2000, 2), pillars(0.6, 0.5));
  acc.add_valid(facts(true, 30.0, 3000, 1), pillars(0.75, 0.75));
  acc.add_failure(EpisodeStatus::kFailureStub, 1);
  acc.add_failure(EpisodeStatus::kInvalid, 3);
  const ModelSummary s = acc.summarize(10, 1.96);
  EXPECT_EQ(s.model, "prov/model");
  EXPECT_EQ(s.domain, "uav");
  EXPECT_EQ(s.files, 5);
  EXPECT_EQ(s.n, 3);
  EXPECT_EQ(s.n_fail, 2);
  EXPECT_EQ(s.n_invalid, 1);
  EXPECT_DOUBLE_EQ(s.mean, 0.75);
  const double sd = std::sqrt((0.15 * 0.15 + 0.15 * 0.15 + 0.0) / 3.0);  // population
  EXPECT_NEAR(s.ci95, 1.96 * sd / std::sqrt(3.0), 1e-15);
  EXPECT_DOUBLE_EQ(s.success_rate, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.gen_fail_rate, 2.0 / 5.0);
  EXPECT_DOUBLE_EQ(s.reliability, 3.0 / 5.0);
  EXPECT_DOUBLE_EQ(s.coverage, 3.0 / 10.0);
  EXPECT_EQ(s.total_attempt_calls, 1 + 2 + 1 + 1 + 3);
  EXPECT_DOUBLE_EQ(s.mean_attempts_used, 8.0 / 5.0);
  EXPECT_DOUBLE_EQ(s.call_efficiency, 1.0);  // min(1, 10 / 8)
  EXPECT_DOUBLE_EQ(s.alpha3_rel, 0.75 * 0.6 * 0.3 * 1.0);
  EXPECT_DOUBLE_EQ(s.pillars.sp, 0.75);
  EXPECT_DOUBLE_EQ(s.pillars.nr, 0.8);
  EXPECT_DOUBLE_EQ(s.mean_gen_time_s, 20.0);
  EXPECT_DOUBLE_EQ(s.mean_total_tokens, 3000.0);
  EXPECT_DOUBLE_EQ(s.alpha3_per_second, s.alpha3_rel / 20.0);
  EXPECT_DOUBLE_EQ(s.alpha3_per_1k_tokens, s.alpha3_rel / 3.0);

  const ModelSummary tight = acc.summarize(4, 1.96);
  EXPECT_DOUBLE_EQ(tight.coverage, 0.75);
  EXPECT_DOUBLE_EQ(tight.call_efficiency, 4.0 / 8.0);
  EXPECT_DOUBLE_EQ(tight.alpha3_rel, 0.75 * 0.6 * 0.75 * 0.5);
  EXPECT_DOUBLE_EQ(acc.summarize(2, 1.96).coverage, 1.0);  // capped
}

TEST(ModelAccumulator, NoValidEpisodeReportsZeroes) {
  ModelAccumulator acc("m", "uav");
  acc.add_failure(EpisodeStatus::kFailureStub, 1);
  acc.add_failure(EpisodeStatus::kFailureStub, 1);
  const ModelSummary s = acc.summarize(50, 1.96);
  EXPECT_EQ(s.n, 0);
  EXPECT_EQ(s.n_fail, 2);
  EXPECT_DOUBLE_EQ(s.mean, 0.0);
  EXPECT_DOUBLE_EQ(s.ci95, 0.0);
  EXPECT_DOUBLE_EQ(s.reliability, 0.0);
  EXPECT_DOUBLE_EQ(s.gen_fail_rate, 1.0);
  EXPECT_DOUBLE_EQ(s.alpha3_rel, 0.0);
  EXPECT_DOUBLE_EQ(s.alpha3_per_second, 0.0);
  EXPECT_DOUBLE_EQ(s.alpha3_per_1k_tokens, 0.0);
  EXPECT_EQ(s.total_attempt_calls, 2);
  EXPECT_DOUBLE_EQ(s.call_efficiency, 1.0);
  EXPECT_FALSE(std::isnan(s.mean_gen_time_s));
}

TEST(ModelAccumulator, VarianceIsStableForManyNearlyEqualScores) {
  ModelAccumulator acc("m", "uav");
  // 100 000 scores around 0.97 with a tiny spread: a naive running sum drifts by ~1e-12 and a
  // naive sum of squares would lose the spread.
  for (int i = 0; i < 100000; ++i) {
    acc.add_valid(facts(true, 1, 1, 1), pillars(0.97 + ((i % 2) ? 1e-6 : -1e-6), 1.0));
  }
  const ModelSummary s = acc.summarize(100000, 1.96);
  EXPECT_NEAR(s.mean, 0.97, 1e-15);
  EXPECT_NEAR(s.ci95, 1.96 * 1e-6 / std::sqrt(100000.0), 1e-14);
}

TEST(MedianTurns, OddEvenAndEmpty) {
  EXPECT_FALSE(median_turns({}).has_value());
  EXPECT_FALSE(median_turns({0, 0, 0}).has_value());
  std::vector<uint64_t> h(13, 0);
  h[8] = 1;
  h[10] = 1;
  h[12] = 1;
  EXPECT_DOUBLE_EQ(*median_turns(h), 10.0);
  h[12] = 2;  // 8, 10, 12, 12 -> (10 + 12) / 2
  EXPECT_DOUBLE_EQ(*median_turns(h), 11.0);
  std::vector<uint64_t> one(10, 0);
  one[9] = 7;
  EXPECT_DOUBLE_EQ(*median_turns(one), 9.0);
}

}  // namespace
}  // namespace a3::eval
