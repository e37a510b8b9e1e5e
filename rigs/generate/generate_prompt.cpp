// The prompts of `a3rig generate`.
#include "rigs/generate/generate_prompt.hpp"

#include <cstdio>

namespace a3::rigs {
namespace {

constexpr std::size_t kProblemsQuoted = 8;

constexpr const char* kEpisodeFormat = R"(An episode is one JSON object with exactly these keys:
- "initial_state": the scenario's initial_state, copied as given.
- "dialogue": an array of 8 to 12 turns. Each turn is
  {"turn": N (1, 2, ...), "speaker": "agent" or "user", "intent": a short snake_case string,
   "actions": [...], "obs": [...], "net": {...}}.
  Speakers alternate strictly (agent, user, agent, ...); no other speaker exists.
  An action is either an MCP tool call {"type": "mcp", "name": TOOL, "args": {...}} or an A2A
  task {"type": "a2a", "task": TASK, "to": PEER, "payload": {...}}.
  Every action is answered in the same turn's "obs": an MCP call by {"tool": TOOL, "result": {...}},
  an A2A task by {"task": TASK, "from": PEER, "status": "ok" or another status, "payload": {...}}.
  MCP tools include read_telemetry, set_waypoint, activate_sensor, capture_image, set_altitude,
  execute_maneuver, navigate_to, switch_network_slice, check_geofence, land, takeoff,
  return_to_home, adjust_speed. A2A tasks include collision_avoidance, request_weather_update,
  swarm_formation, request_swarm_coverage, swarm_status_check, path_plan.
  "net" is the 6G network state during the turn: {"slice": "URLLC" | "eMBB" | "mMTC",
  "lat_ms": number, "jitter_ms": number, "loss_pct": number, "throughput_mbps": number,
  "edge_load": number between 0 and 1}.
- "final_state": the state at the end, with the same shape as initial_state (pose, speed,
  energy, sensors, payloads, policy, safety_flags), consistent with the dialogue.
- "success": true or false, whether the mission was accomplished.
The UAV must stay within the airspace's alt_bounds and geofence, keep its battery above 5 %,
and end with safety_flags nfz_violation and separation_breach false.)";

constexpr const char* kRolesRule =
    "Speakers: only \"agent\" and \"user\", strictly alternating, starting with \"agent\"; never "
    "\"system\", \"assistant\" or any other role. Between 8 and 12 turns.";

constexpr const char* kFormatRule =
    "Format: reply with the JSON object only: no prose, no markdown fence, no comments. Every number is a "
    "JSON number (never a word such as \"low\"); every action has its observation in the same turn; keep "
    "initial_state exactly as given.";

}  // namespace

std::string scenario_id(int number) {
  char id[16];
  std::snprintf(id, sizeof id, "sc-%04d", number);
  return id;
}

std::string generate_system_prompt(int attempt) {
  std::string out =
      "You write benchmark episodes for α³-Bench: the dialogue of an LLM agent flying a UAV mission over a 6G "
      "network with a human supervisor (the user), using MCP tools and A2A tasks with peer agents.\n\n";
  out += kEpisodeFormat;
  out += "\n\nReply with one JSON object: the episode.";
  if (attempt >= 2) out += std::string("\n\n") + kRolesRule;
  if (attempt >= 3) out += std::string("\n") + kFormatRule;
  return out;
}

std::string generate_user_prompt(const GenerateScenario& scenario, int64_t seed, int attempt,
                                 const GenerateFailure& previous) {
  std::string out;
  out += "scenario_id: " + scenario_id(scenario.number) + "\n";
  out += "episode_seed: " + std::to_string(seed) + "\n";
  out += "attempt: " + std::to_string(attempt) + " of " + std::to_string(kGenerateMaxAttempts) + "\n\n";
  if (attempt >= 2 && !previous.problems.empty()) {
    out += "Your previous episode was rejected:\n";
    for (std::size_t i = 0; i < previous.problems.size() && i < kProblemsQuoted; ++i) {
      out += "- " + previous.problems[i] + "\n";
    }
    if (previous.problems.size() > kProblemsQuoted) {
      out += "- (" + std::to_string(previous.problems.size() - kProblemsQuoted) + " more)\n";
    }
    out += std::string(attempt >= 3 ? "This is the last attempt. " : "") + "Fix these and write the episode again.\n";
    out += std::string(kRolesRule) + "\n";
    if (attempt >= 3) out += std::string(kFormatRule) + "\n";
    out += "\n";
  }
  if (!scenario.mission.empty()) out += "Mission: " + scenario.mission + "\n\n";
  out += "Write a complete episode (seed " + std::to_string(seed) +
         " for variety between episodes of the same scenario) starting from this initial_state:\n```json\n";
  out += scenario.initial_state.dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  out += "\n```\n";
  return out;
}

std::vector<agent::llm::ChatMessage> generate_messages(const GenerateScenario& scenario, int64_t seed, int attempt,
                                                       const GenerateFailure& previous) {
  return {{"system", generate_system_prompt(attempt)},
          {"user", generate_user_prompt(scenario, seed, attempt, previous)}};
}

}  // namespace a3::rigs
