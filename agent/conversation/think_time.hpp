// Think time: latency added to an agent's turns, fixed or drawn from a distribution, so that
// "how late can the agent answer" can be swept. Specs:
//   "2.5" or "fixed:2.5"         2.5 s every turn
//   "uniform:1,4"                uniform between 1 and 4 s
//   "normal:3,1"                 mean 3 s, standard deviation 1 s (truncated at 0)
//   "lognormal:3,0.5"            median 3 s, log-space sigma 0.5
//   "exp:3"                      exponential, mean 3 s
//   "model:<name>"               a model of the paper (SPEC §8): its published mean generation
//                                time per episode spread over 6 agent turns, lognormal with
//                                sigma 0.5 (e.g. "model:Claude-Opus-4.5")
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "agent/conversation/agent.hpp"
#include "common/rng.hpp"

namespace a3::agent {

class ThinkTime {
 public:
  // Throws std::invalid_argument naming the bad spec and the accepted forms.
  static ThinkTime parse(const std::string& spec);
  double sample_s(common::Rng& rng) const;
  double mean_s() const;
  const std::string& spec() const { return spec_; }
  bool is_zero() const { return kind_ == Kind::kFixed && a_ == 0.0; }

 private:
  enum class Kind { kFixed, kUniform, kNormal, kLogNormal, kExponential };
  std::string spec_;
  Kind kind_ = Kind::kFixed;
  double a_ = 0.0, b_ = 0.0;
};

struct ModelLatencyProfile {
  std::string name;
  double mean_generation_time_s;  // per episode, as published
  double mean_total_tokens;
};
// The sixteen models of the paper's Table (SPEC §8), plus ChatGPT-4o.
const std::vector<ModelLatencyProfile>& model_latency_profiles();
// The profile named `name`, ignoring case ("claude-haiku-4.5" is "Claude-Haiku-4.5"); null if none.
const ModelLatencyProfile* find_model_latency_profile(const std::string& name);

// Adds think time to another agent's decisions (on top of its own latency).
class ThinkTimeAgent final : public Agent {
 public:
  ThinkTimeAgent(std::unique_ptr<Agent> inner, ThinkTime think_time, uint64_t seed);
  std::string name() const override { return inner_->name(); }
  AgentDecision decide(const AgentContext& context) override;
  void on_mission_time(double mission_time_s) override { inner_->on_mission_time(mission_time_s); }
  void on_dialogue(const std::vector<Turn>& dialogue, bool over, const std::string& why) override {
    inner_->on_dialogue(dialogue, over, why);
  }
  void stop_deciding() override { inner_->stop_deciding(); }

 private:
  std::unique_ptr<Agent> inner_;
  ThinkTime think_time_;
  common::Rng rng_;
};

}  // namespace a3::agent
