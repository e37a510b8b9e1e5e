// Replaying recorded agent turns.
#include "agent/conversation/replay_agent.hpp"

#include "common/json_file.hpp"

namespace a3::agent {

ReplayAgent ReplayAgent::from_file(const std::filesystem::path& file) {
  return ReplayAgent(common::load_json_file(file), file.string());
}

ReplayAgent::ReplayAgent(const nlohmann::json& episode, const std::string& where) {
  const auto& dialogue = common::require_array(episode, "dialogue", where);
  for (std::size_t i = 0; i < dialogue.size(); ++i) {
    const auto& t = dialogue[i];
    const std::string w = where + "/dialogue/" + std::to_string(i);
    if (common::require_string(t, "speaker", w) != "agent") continue;
    common::require_array(t, "actions", w);
    turns_.push_back(t);
  }
  if (turns_.empty()) throw common::InputError(where + ": the episode has no agent turn to replay");
  if (episode.contains("_meta") && episode["_meta"].is_object()) {
    const auto& meta = episode["_meta"];
    const double gen_s = common::number_or(meta, "gen_time_s", 0.0, where + "/_meta");
    latency_per_turn_s_ = gen_s / static_cast<double>(turns_.size());
    if (meta.contains("usage") && meta["usage"].is_object()) {
      for (const char* key : {"prompt_tokens", "completion_tokens", "total_tokens"}) {
        const double v = common::number_or(meta["usage"], key, 0.0, where + "/_meta/usage");
        usage_per_turn_[key] = static_cast<int64_t>(v / static_cast<double>(turns_.size()));
      }
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
