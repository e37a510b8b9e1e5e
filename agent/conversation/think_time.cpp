// Think-time distributions and the per-model latency profiles.
#include "agent/conversation/think_time.hpp"

#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/number_list.hpp"

namespace a3::agent {
namespace {

constexpr double kAgentTurnsPerEpisode = 6.0;
constexpr double kModelSigma = 0.5;

const char* kForms = "expected a number of seconds, fixed:S, uniform:A,B, normal:MEAN,SD, lognormal:MEDIAN,SIGMA, exp:MEAN or model:NAME";

std::vector<double> numbers(const std::string& text, const std::string& spec) {
  return common::parse_number_list(text, spec, {"think time", true});
}

}  // namespace

const std::vector<ModelLatencyProfile>& model_latency_profiles() {
  static const std::vector<ModelLatencyProfile> kProfiles = {
      {"ChatGPT-4o", 10.58, 4032}, {"GPT-5.1-Chat", 18.99, 2854}, {"GPT-5.2-Chat", 26.01, 3914},
      {"Gemini-2.5-Flash", 27.09, 5759}, {"Claude-Haiku-4.5", 42.79, 7827}, {"Claude-Opus-4.5", 57.04, 5436},
      {"Claude-Sonnet-4.5", 62.72, 7779}, {"GPT-4.1-mini", 78.30, 4754}, {"Qwen3-Max", 89.62, 5329},
      {"Mistral-Large-2512", 95.20, 5914}, {"Qwen3-235B-A22B", 105.15, 5652}, {"Mistral-Medium-3.1", 115.78, 7370},
      {"Gemini-3-Pro-Preview", 119.84, 7526}, {"GPT-5-mini", 142.56, 8537}, {"DeepSeek-V3.2-exp", 147.42, 5010},
      {"DeepSeek-V3.2", 290.78, 5390}, {"Kimi-K2-Thinking", 314.03, 7631}};
  return kProfiles;
}

const ModelLatencyProfile* find_model_latency_profile(const std::string& name) {
  auto lower = [](std::string x) {
    for (char& c : x) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return x;
  };
  for (const auto& p : model_latency_profiles()) {
    if (lower(p.name) == lower(name)) return &p;
  }
  return nullptr;
}

ThinkTime ThinkTime::parse(const std::string& spec) {
  ThinkTime t;
  t.spec_ = spec;
  const auto colon = spec.find(':');
  const std::string kind = colon == std::string::npos ? "fixed" : spec.substr(0, colon);
  const std::string args = colon == std::string::npos ? spec : spec.substr(colon + 1);
  if (kind == "model") {
    if (const ModelLatencyProfile* p = find_model_latency_profile(args)) {
      t.kind_ = Kind::kLogNormal;
      // lognormal with this mean: median = mean / exp(σ²/2)
      t.a_ = p->mean_generation_time_s / kAgentTurnsPerEpisode / std::exp(kModelSigma * kModelSigma / 2.0);
      t.b_ = kModelSigma;
      return t;
    }
    std::string names;
    for (const auto& p : model_latency_profiles()) names += (names.empty() ? "" : ", ") + p.name;
    throw std::invalid_argument("think time '" + spec + "': unknown model (known: " + names + ")");
  }
  const std::vector<double> v = numbers(args, spec);
  auto need = [&](std::size_t n) {
    if (v.size() != n) throw std::invalid_argument("think time '" + spec + "': " + kForms);
  };
  if (kind == "fixed") {
    need(1);
    t.kind_ = Kind::kFixed;
    t.a_ = v[0];
  } else if (kind == "uniform") {
    need(2);
    if (v[1] < v[0]) throw std::invalid_argument("think time '" + spec + "': uniform needs A <= B");
    t.kind_ = Kind::kUniform;
    t.a_ = v[0];
    t.b_ = v[1];
  } else if (kind == "normal") {
    need(2);
    t.kind_ = Kind::kNormal;
    t.a_ = v[0];
    t.b_ = v[1];
  } else if (kind == "lognormal") {
    need(2);
    if (v[0] <= 0.0) throw std::invalid_argument("think time '" + spec + "': the median must be > 0");
    t.kind_ = Kind::kLogNormal;
    t.a_ = v[0];
    t.b_ = v[1];
  } else if (kind == "exp") {
    need(1);
    t.kind_ = Kind::kExponential;
    t.a_ = v[0];
  } else {
    throw std::invalid_argument("think time '" + spec + "': unknown kind '" + kind + "' (" + kForms + ")");
  }
  return t;
}

double ThinkTime::sample_s(common::Rng& rng) const {
  switch (kind_) {
    case Kind::kFixed: return a_;
    case Kind::kUniform: return rng.uniform(a_, b_);
    case Kind::kNormal: return std::max(0.0, rng.normal(a_, b_));
    case Kind::kLogNormal: return rng.lognormal(std::log(a_), b_);
    case Kind::kExponential: return a_ > 0.0 ? rng.exponential(a_) : 0.0;
  }
  return 0.0;
}

double ThinkTime::mean_s() const {
  switch (kind_) {
    case Kind::kFixed: return a_;
    case Kind::kUniform: return 0.5 * (a_ + b_);
    case Kind::kNormal: return a_;
    case Kind::kLogNormal: return a_ * std::exp(b_ * b_ / 2.0);
    case Kind::kExponential: return a_;
  }
  return 0.0;
}

ThinkTimeAgent::ThinkTimeAgent(std::unique_ptr<Agent> inner, ThinkTime think_time, uint64_t seed)
    : inner_(std::move(inner)), think_time_(std::move(think_time)), rng_(common::RngStreams(seed).stream("agent.think_time")) {}

AgentDecision ThinkTimeAgent::decide(const AgentContext& context) {
  AgentDecision d = inner_->decide(context);
  d.think_time_s += think_time_.sample_s(rng_);
  return d;
}

}  // namespace a3::agent
