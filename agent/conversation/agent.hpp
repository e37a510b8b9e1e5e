// The agent interface: given the conversation so far and what the ground side knows, decide
// the next agent turn (an intent, words, and zero or more MCP/A2A actions). Implementations:
// scripted (our reference policy), replay (a recorded episode's agent turns), llm (an
// OpenAI-compatible endpoint). decide() may block (an HTTP call); the conversation measures
// it, or takes the latency the agent declares, and lets that time pass in the simulated world
// before the actions leave the ground.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "agent/conversation/turn.hpp"
#include "agent/mission/mission.hpp"
#include "agent/tool_catalog.hpp"

namespace a3::agent {

struct AgentContext {
  const Mission* mission = nullptr;
  nlohmann::json initial_state;            // the scenario's α³-Bench initial_state
  nlohmann::json airspace;                  // no-fly zones, traffic (ids, not futures), geofence
  const std::vector<Turn>* dialogue = nullptr;
  const ToolCatalog* tools = nullptr;
  nlohmann::json net;                       // n_t now
  nlohmann::json last_telemetry;            // latest read_telemetry result seen (may be null)
  int turn_number = 1;                      // of the turn being decided
  int max_turns = 12;
  double mission_time_s = 0.0;
};

struct AgentDecision {
  std::string intent;
  std::string text;
  nlohmann::json actions = nlohmann::json::array();
  // The agent's own latency: what decide() took (an LLM call, measured) or declares (the
  // replay agent's recorded timing). In virtual time it is charged to simulated time; in real
  // time a blocking agent's wall time passes by itself.
  double latency_s = 0.0;
  // Extra think time added on top (--think-time), charged in both runtimes.
  double think_time_s = 0.0;
  nlohmann::json usage = nlohmann::json::object();  // prompt/completion/total tokens
  int attempts = 1;
  // One entry per attempt (an LLM agent's retries): outcome, problems, usage, wall time.
  nlohmann::json attempt_log = nlohmann::json::array();
  std::string error;  // a failed decision (after all attempts): the turn has no actions
};

class Agent {
 public:
  virtual ~Agent() = default;
  virtual std::string name() const = 0;
  virtual AgentDecision decide(const AgentContext& context) = 0;
};

}  // namespace a3::agent
