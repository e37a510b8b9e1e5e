// The agent interface: given the conversation so far and what the ground side knows, decide
// the next agent turn (an intent, words, and zero or more MCP/A2A actions). Implementations:
// scripted (our reference policy), replay (a recorded episode's agent turns), llm (an
// OpenAI-compatible endpoint). decide() may block (an HTTP call); the conversation measures
// it, or takes the latency the agent declares, and lets that time pass in the simulated world
// before the actions leave the ground.
//
// A turn may take several steps (an MCP client calls one tool at a time and needs each result
// before its next call): a decision with turn_continues set dispatches its actions and, once
// their observations are in, decide() is called again for the same turn, with the turn so far
// in the context. The turn's message goes up the link at its first step; latencies add up over
// the steps; the turn's intent and text are those of its last step.
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
  // The turn so far (a multi-step turn): the actions of its earlier steps and their
  // observations, index for index. Empty at step 1.
  int step = 1;
  nlohmann::json turn_actions = nlohmann::json::array();
  nlohmann::json turn_obs = nlohmann::json::array();
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
  // Dispatch these actions, then call decide() again for the same turn when their
  // observations are in. Ignored for a decision without actions or with an error (a step
  // that does nothing cannot continue the turn).
  bool turn_continues = false;
};

class Agent {
 public:
  virtual ~Agent() = default;
  virtual std::string name() const = 0;
  virtual AgentDecision decide(const AgentContext& context) = 0;
  // What the conversation tells an agent between its decisions (an agent driven from outside,
  // such as an MCP client's, needs it; others ignore it). Called on the conversation's thread.
  // Mission time, about once a simulated second:
  virtual void on_mission_time(double /*mission_time_s*/) {}
  // After every completed turn, and once more with `over` set when the dialogue has ended
  // (`why`: e.g. "turn budget used").
  virtual void on_dialogue(const std::vector<Turn>& /*dialogue*/, bool /*over*/, const std::string& /*why*/) {}
  // The conversation is being torn down (the run ends): a decide() blocked on another thread,
  // waiting for something outside, must return soon (with any decision). Any thread.
  virtual void stop_deciding() {}
};

}  // namespace a3::agent
