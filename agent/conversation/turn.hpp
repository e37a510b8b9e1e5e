// One turn of a conversational episode (SPEC §1): who speaks, the intent, the structured
// actions, one observation per action, and the 6G network vector n_t at the turn: the state
// of the link when the turn's message crossed it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace a3::agent {

// At most this many actions in one agent turn (all its steps together). The busiest turn of the
// α³-Bench public corpus has 3 actions (200 episodes); a reply with thousands would flood the
// emulated link and the vehicle's tool server with work no supervisor asked for. The actions
// beyond it are not sent: the turn's _rig.refused_actions counts them.
inline constexpr std::size_t kMaxActionsPerTurn = 16;

struct Turn {
  int number = 0;             // 1-based
  std::string speaker;        // "agent" | "user"
  std::string intent;
  nlohmann::json actions = nlohmann::json::array();
  nlohmann::json obs = nlohmann::json::array();
  nlohmann::json net = nlohmann::json::object();  // slice, lat_ms, jitter_ms, loss_pct, throughput_mbps, edge_load
  // What only the rig knows (the episode's _rig section).
  double started_s = 0.0;       // mission time when the turn began
  double decided_s = 0.0;       // when the speaker's decision was ready (after think time)
  double finished_s = 0.0;      // when the last observation arrived (or timed out)
  // The turn's message on the link: handed to it (sent_s) and delivered (delivered_s; < 0 when
  // lost or dropped). `net` is the link's n_t when it crossed.
  double sent_s = -1.0;
  double delivered_s = -1.0;
  double think_time_s = 0.0;    // latency charged to the turn (measured or declared), all steps
  int steps = 1;                // decisions the agent took for this turn (multi-step turns)
  nlohmann::json usage = nlohmann::json::object();  // tokens, for LLM agents
  int attempts = 1;
  nlohmann::json attempt_log = nlohmann::json::array();  // AgentDecision::attempt_log
  int refused_actions = 0;      // decided beyond kMaxActionsPerTurn, not sent
  std::string text;             // what the speaker said, in words

  // The α³-Bench turn object.
  nlohmann::json to_json() const;
  // The status answered to the i-th action (observation_status of its observation; "timeout"
  // when it has none).
  std::string answer_status(std::size_t i) const;
};

// The status an observation answers with: an MCP tool's `result.status`, an A2A answer's
// `status`; "timeout" when there is no answer (lost: the conversation writes a timeout
// observation, or none at all), "" when answered without a status (read_telemetry).
std::string observation_status(const nlohmann::json& obs);

}  // namespace a3::agent
