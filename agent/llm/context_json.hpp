// The machine-readable form of an agent turn's context (AgentContext ⇄ JSON). The llm agent's
// prompt carries it as a fenced ```json block, so that a model reads the same facts a program
// can: `a3rig serve-model --responder scripted` rebuilds the AgentContext from it and answers
// with the scripted policy's decision. The mission is written without its hidden targets.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "agent/conversation/agent.hpp"

namespace a3::agent::llm {

// The block's marker key and version: {"a3_context": 1, ...}.
inline constexpr const char* kContextMarker = "a3_context";
inline constexpr int kContextVersion = 1;

struct DialogueLimits {
  // When the dialogue's JSON is longer than this, the observations of the oldest turns are
  // replaced by their status, oldest first, until it fits; the newest keep_full_turns turns
  // are never shortened. ~4 characters per token: 48,000 characters is ~12k tokens, far
  // above the default 12-turn mission (a few thousand characters), so that in the usual case
  // nothing is cut and the block round-trips exactly.
  std::size_t max_dialogue_chars = 48'000;
  std::size_t keep_full_turns = 4;
};

// The mission with every objective field the agents use (hidden targets left out).
nlohmann::json mission_to_json(const Mission& mission);
// Throws std::invalid_argument naming the field ("mission/objectives/1/area: ...").
Mission mission_from_json(const nlohmann::json& j, const std::string& where = "mission");

// One turn as the dialogue of the context holds it: turn, speaker, intent, text, actions,
// obs, net, t_s (mission time at the start of the turn).
nlohmann::json turn_to_json(const Turn& turn);

// The whole context: marker, turn, max_turns, mission_time_s, mission, initial_state,
// airspace, net, telemetry (null before any read_telemetry), dialogue, and
// dialogue_shortened (how many turns' observations were cut; absent when none).
nlohmann::json context_to_json(const AgentContext& context, const DialogueLimits& limits = {});

// An AgentContext rebuilt from the JSON, owning what the context points to.
struct RebuiltContext {
  Mission mission;
  std::vector<Turn> dialogue;
  nlohmann::json initial_state, airspace, net, telemetry;
  int turn_number = 1;
  int max_turns = 12;
  double mission_time_s = 0.0;
  // A view pointing into this object (keep it alive while the view is used).
  AgentContext view(const ToolCatalog& tools) const;
};
// Throws std::invalid_argument naming the field ("context/dialogue/2/actions: expected an array").
RebuiltContext context_from_json(const nlohmann::json& j);

// The context block in a message's text: the first fenced ```json block (or, failing that,
// any JSON object in the text) whose object carries the marker. nullopt when there is none.
std::optional<nlohmann::json> find_context_block(const std::string& text);

}  // namespace a3::agent::llm
