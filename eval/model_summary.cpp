// Streaming model aggregates.
#include "eval/model_summary.hpp"

#include <algorithm>
#include <cmath>

namespace a3::eval {

void CompensatedSum::add(double x) {
  const double t = sum_ + x;
  compensation_ += std::abs(sum_) >= std::abs(x) ? (sum_ - t) + x : (x - t) + sum_;
  sum_ = t;
}

ModelAccumulator::ModelAccumulator(std::string model, std::string domain)
    : model_(std::move(model)), domain_(std::move(domain)) {}

void ModelAccumulator::add_valid(const EpisodeFacts& facts, const Pillars& p) {
  ++files_;
  ++valid_;
  attempts_ += facts.attempts_used;
  if (facts.success) ++successes_;
  alpha3_sum_.add(p.alpha3);
  const double delta = p.alpha3 - welford_mean_;
  welford_mean_ += delta / static_cast<double>(valid_);
  welford_m2_ += delta * (p.alpha3 - welford_mean_);
  to_sum_.add(p.to);
  sp_sum_.add(p.sp);
  tc_sum_.add(p.tc);
  iq_sum_.add(p.iq);
  nr_sum_.add(p.nr);
  cc_sum_.add(p.cc);
  gen_time_sum_s_.add(facts.gen_time_s);
  tokens_sum_.add(facts.total_tokens);
}

void ModelAccumulator::add_failure(EpisodeStatus status, int64_t attempts_used) {
  ++files_;
  (status == EpisodeStatus::kFailureStub ? stubs_ : invalid_) += 1;
  attempts_ += std::max<int64_t>(attempts_used, 1);
}

ModelSummary ModelAccumulator::summarize(int64_t budget, double ci95_z) const {
  ModelSummary s;
  s.model = model_;
  s.domain = domain_;
  s.files = files_;
  s.n = valid_;
  s.n_fail = stubs_ + invalid_;
  s.n_invalid = invalid_;
  s.budget = budget;
  s.total_attempt_calls = attempts_;
  const double n = static_cast<double>(valid_);
  if (valid_ > 0) {
    s.mean = alpha3_sum_.value() / n;
    s.ci95 = ci95_z * std::sqrt(welford_m2_ / n) / std::sqrt(n);
    s.success_rate = static_cast<double>(successes_) / n;
    s.pillars = {to_sum_.value() / n, sp_sum_.value() / n, tc_sum_.value() / n,
                 iq_sum_.value() / n, nr_sum_.value() / n, cc_sum_.value() / n};
    s.mean_gen_time_s = gen_time_sum_s_.value() / n;
    s.mean_total_tokens = tokens_sum_.value() / n;
  }
  const double files = static_cast<double>(files_);
  s.gen_fail_rate = files_ > 0 ? static_cast<double>(s.n_fail) / files : 0.0;
  s.reliability = valid_ + s.n_fail > 0 ? n / static_cast<double>(valid_ + s.n_fail) : 0.0;
  s.coverage = budget > 0 ? std::min(1.0, n / static_cast<double>(budget)) : 0.0;
  s.call_efficiency =
      attempts_ > 0 ? std::min(1.0, static_cast<double>(budget) / static_cast<double>(attempts_))
                    : 0.0;
  s.mean_attempts_used = files_ > 0 ? static_cast<double>(attempts_) / files : 0.0;
  s.alpha3_rel = s.mean * s.reliability * s.coverage * s.call_efficiency;
  s.alpha3_per_second = s.mean_gen_time_s > 0.0 ? s.alpha3_rel / s.mean_gen_time_s : 0.0;
  s.alpha3_per_1k_tokens =
      s.mean_total_tokens > 0.0 ? s.alpha3_rel / (s.mean_total_tokens / 1000.0) : 0.0;
  return s;
}

}  // namespace a3::eval
