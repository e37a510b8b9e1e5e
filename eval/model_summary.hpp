// Model-level aggregation (SPEC-alpha3.md §3): a streaming accumulator per (model, domain) that
// holds sums, never the episodes, and the leaderboard row it produces.
#pragma once

#include <cstdint>
#include <string>

#include "eval/episode_reader.hpp"
#include "eval/pillars.hpp"

namespace a3::eval {

struct PillarMeans {
  double to = 0.0, sp = 0.0, tc = 0.0, iq = 0.0, nr = 0.0, cc = 0.0;
};

// One leaderboard row; the fields and their order are the public release's columns.
struct ModelSummary {
  std::string model;
  std::string domain;
  double mean = 0.0;
  double ci95 = 0.0;
  int64_t n = 0;
  double success_rate = 0.0;
  double gen_fail_rate = 0.0;
  double reliability = 0.0;
  double coverage = 0.0;
  double alpha3_rel = 0.0;
  PillarMeans pillars;
  double mean_gen_time_s = 0.0;
  double mean_total_tokens = 0.0;
  double alpha3_per_second = 0.0;
  double alpha3_per_1k_tokens = 0.0;
  int64_t total_attempt_calls = 0;
  double mean_attempts_used = 0.0;
  double call_efficiency = 0.0;
  // Not release columns: what the ratios were computed from.
  int64_t files = 0;
  int64_t n_fail = 0;  // failure stubs + invalid files
  int64_t n_invalid = 0;
  int64_t budget = 0;
};

// Neumaier-compensated sum: a corpus of 10^5 episodes sums to the last bit, not to ~1e-12.
class CompensatedSum {
 public:
  void add(double x);
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0.0, compensation_ = 0.0;
};

class ModelAccumulator {
 public:
  ModelAccumulator(std::string model, std::string domain);

  void add_valid(const EpisodeFacts& facts, const Pillars& pillars);
  // A failure stub or an invalid file: counts as a failure; attempts as SPEC §3 says.
  void add_failure(EpisodeStatus status, int64_t attempts_used);

  // The row for an episode budget B (> 0), with ci95's z from the profile.
  ModelSummary summarize(int64_t budget, double ci95_z) const;

  const std::string& model() const { return model_; }
  const std::string& domain() const { return domain_; }

 private:
  std::string model_, domain_;
  int64_t files_ = 0, valid_ = 0, stubs_ = 0, invalid_ = 0, attempts_ = 0, successes_ = 0;
  CompensatedSum alpha3_sum_;
  double welford_mean_ = 0.0, welford_m2_ = 0.0;  // population variance of α³
  CompensatedSum to_sum_, sp_sum_, tc_sum_, iq_sum_, nr_sum_, cc_sum_;
  CompensatedSum gen_time_sum_s_, tokens_sum_;
};

}  // namespace a3::eval
