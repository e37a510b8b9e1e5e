// Replaying recorded agent turns.
#include "agent/conversation/replay_agent.hpp"

#include "common/json_file.hpp"  // InputError

namespace a3::agent {

ReplayAgent ReplayAgent::from_file(const std::filesystem::path& file) {
  return ReplayAgent(episode::Episode::load(file));
}

ReplayAgent::ReplayAgent(const episode::Episode& episode) {
  for (const std::size_t i : episode.turns_of("agent")) {
    episode.actions(i);  // every replayed turn has its actions (an InputError naming it if not)
    turns_.emplace_back(episode.turn(i));
  }
  if (turns_.empty()) throw common::InputError(episode.where() + ": the episode has no agent turn to replay");
  const episode::EpisodeMeta meta = episode.meta();
  const auto turns = static_cast<double>(turns_.size());
  latency_per_turn_s_ = meta.gen_time_s.value_or(0.0) / turns;
  if (meta.usage) {
    for (const char* key : {"prompt_tokens", "completion_tokens", "total_tokens"}) {
      usage_per_turn_[key] = static_cast<int64_t>(static_cast<double>(meta.usage_count(key)) / turns);
    }
  }
}

AgentDecision ReplayAgent::decide(const AgentContext&) {
  AgentDecision d;
  if (next_ >= turns_.size()) {
    d.intent = "no_more_recorded_turns";
    d.text = "The recording has no more agent turns.";
    return d;
  }
  const auto& t = turns_[next_++];
  d.intent = t.value("intent", "");
  d.text = "Replayed turn " + std::to_string(t.value("turn", 0)) + ".";
  d.actions = t["actions"];
  d.latency_s = latency_per_turn_s_;
  d.usage = usage_per_turn_;
  return d;
}

}  // namespace a3::agent
