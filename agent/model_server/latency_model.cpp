// The model server's latency models.
#include "agent/model_server/latency_model.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/number_list.hpp"
#include "common/text_format.hpp"

namespace a3::agent::model_server {
namespace {

const char* kForms =
    "expected recorded, a number of seconds, fixed:S, uniform:A,B, normal:MEAN,SD, lognormal:MEDIAN,SIGMA, exp:MEAN, "
    "model:NAME, model-episode:NAME or tokens:PREFILL_TOK_PER_S,DECODE_TOK_PER_S[,TTFT_S]";

std::string fmt(double x) { return common::formatted("%.4g", x); }

double tokens(const nlohmann::json& usage, const char* key) {
  if (!usage.is_object()) return 0.0;
  const auto it = usage.find(key);
  return it != usage.end() && it->is_number() ? std::max(0.0, it->get<double>()) : 0.0;
}

std::vector<double> numbers(const std::string& text, const std::string& spec) {
  return common::parse_number_list(text, spec, {"latency", false});
}

}  // namespace

LatencyModel LatencyModel::parse(const std::string& spec, double time_scale) {
  if (!std::isfinite(time_scale) || time_scale < 0.0) {
    throw std::invalid_argument("time scale " + fmt(time_scale) + ": must be a number >= 0");
  }
  LatencyModel m;
  m.spec_ = spec;
  m.time_scale_ = time_scale;
  if (spec == "recorded") {
    m.kind_ = Kind::kRecorded;
    return m;
  }
  if (spec.rfind("tokens:", 0) == 0) {
    const std::vector<double> v = numbers(spec.substr(7), spec);
    if (v.size() != 2 && v.size() != 3) {
      throw std::invalid_argument("latency '" + spec + "': tokens takes PREFILL_TOK_PER_S,DECODE_TOK_PER_S[,TTFT_S]");
    }
    if (!(v[0] > 0.0) || !(v[1] > 0.0)) {
      throw std::invalid_argument("latency '" + spec + "': token rates must be > 0 tokens per second");
    }
    if (v.size() == 3 && v[2] < 0.0) throw std::invalid_argument("latency '" + spec + "': TTFT must be >= 0 s");
    m.kind_ = Kind::kTokens;
    m.prefill_tok_per_s_ = v[0];
    m.decode_tok_per_s_ = v[1];
    m.ttft_s_ = v.size() == 3 ? v[2] : 0.0;
    return m;
  }
  m.kind_ = Kind::kDistribution;
  try {
    if (spec.rfind("model-episode:", 0) == 0) {
      const std::string name = spec.substr(14);
      m.distribution_ = ThinkTime::parse("model:" + name);
      // ThinkTime spreads the episode's mean over the turns; a request here is the whole episode.
      if (const auto* p = find_model_latency_profile(name)) {
        m.distribution_factor_ = p->mean_generation_time_s / m.distribution_->mean_s();
      }
    } else {
      m.distribution_ = ThinkTime::parse(spec);
    }
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("latency '" + spec + "': " + e.what() + "; a latency is one of: " + kForms);
  }
  return m;
}

double LatencyModel::latency_s(const ResponderReply& reply, common::Rng& rng) const {
  double s = 0.0;
  switch (kind_) {
    case Kind::kRecorded:
      s = reply.latency_s.value_or(0.0);
      break;
    case Kind::kDistribution:
      s = distribution_->sample_s(rng) * distribution_factor_;
      break;
    case Kind::kTokens:
      s = ttft_s_ + tokens(reply.usage, "prompt_tokens") / prefill_tok_per_s_ +
          tokens(reply.usage, "completion_tokens") / decode_tok_per_s_;
      break;
  }
  if (!std::isfinite(s) || s < 0.0) s = 0.0;
  return s * time_scale_;
}

std::optional<double> LatencyModel::mean_s() const {
  if (kind_ != Kind::kDistribution) return std::nullopt;
  return distribution_->mean_s() * distribution_factor_ * time_scale_;
}

std::string LatencyModel::describe() const {
  std::string out;
  switch (kind_) {
    case Kind::kRecorded:
      out = "recorded (the responder's, 0 when it has none)";
      break;
    case Kind::kDistribution:
      out = spec_ + " (mean " + fmt(distribution_->mean_s() * distribution_factor_) + " s per request)";
      break;
    case Kind::kTokens:
      out = "tokens (ttft " + fmt(ttft_s_) + " s, prefill " + fmt(prefill_tok_per_s_) + " tok/s, decode " +
            fmt(decode_tok_per_s_) + " tok/s)";
      break;
  }
  if (time_scale_ != 1.0) out += " x time scale " + fmt(time_scale_);
  return out;
}

}  // namespace a3::agent::model_server
