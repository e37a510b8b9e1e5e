// The replay agent: plays back the agent turns of a recorded episode (an α³-Bench episode file,
// e.g. from the public corpus) in order, with their recorded timing: the episode's generation
// time (_meta.gen_time_s) spread evenly over its agent turns. Tools the rig does not know come
// back as error observations, as for any agent.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <vector>

#include "agent/conversation/agent.hpp"
#include "episode/episode.hpp"

namespace a3::agent {

class ReplayAgent final : public Agent {
 public:
  // Throws common::InputError naming the file and field when it is not a usable episode.
  static ReplayAgent from_file(const std::filesystem::path& episode_file);
  explicit ReplayAgent(const episode::Episode& episode);

  std::string name() const override { return "replay"; }
  AgentDecision decide(const AgentContext& context) override;
  std::size_t turns() const { return turns_.size(); }
  double latency_per_turn_s() const { return latency_per_turn_s_; }

 private:
  std::vector<nlohmann::json> turns_;
  std::size_t next_ = 0;
  double latency_per_turn_s_ = 0.0;
  nlohmann::json usage_per_turn_ = nlohmann::json::object();
};

}  // namespace a3::agent
