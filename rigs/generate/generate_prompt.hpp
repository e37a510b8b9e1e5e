// The messages of `a3rig generate` (the paper's offline protocol, SPEC-alpha3.md §4): the model
// writes one whole α³-Bench episode for a scenario's initial_state. The system message states
// the episode format and its rules; the user message carries the tag lines
//   scenario_id: sc-0013
//   episode_seed: 42
//   attempt: 1 of 3
// (read by `serve-model --responder corpus`, agent/model_server/corpus_responder.hpp), the
// mission when the scenario has one, and the initial_state as a fenced ```json block.
// Attempts 2 and 3 get stricter, as the paper's do after a schema failure: attempt 2 restricts
// the roles (only agent and user, alternating) and names what was wrong; attempt 3 also
// restricts the format (only the JSON object, numbers as numbers, every action answered).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "agent/llm/llm_client.hpp"

namespace a3::rigs {

inline constexpr int kGenerateMaxAttempts = 3;

// One scenario to generate episodes for.
struct GenerateScenario {
  int number = 0;                 // XXXX of the output's sc-XXXX-ep-YY.json
  std::string source;             // where it came from (a file, "built-in NAME"), for messages
  nlohmann::ordered_json initial_state;
  std::string mission;            // a mission description, when the scenario has one
};

// "sc-0013".
std::string scenario_id(int number);

// What went wrong with the previous attempt (empty for attempt 1).
struct GenerateFailure {
  std::vector<std::string> problems;  // violations or the call's error, most important first
};

std::string generate_system_prompt(int attempt);
std::string generate_user_prompt(const GenerateScenario& scenario, int64_t seed, int attempt,
                                 const GenerateFailure& previous);
std::vector<agent::llm::ChatMessage> generate_messages(const GenerateScenario& scenario, int64_t seed, int attempt,
                                                       const GenerateFailure& previous);

}  // namespace a3::rigs
