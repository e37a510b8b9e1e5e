// What an MCP client of the live rig reads, as text and JSON: the mission brief (the
// InitializeResult's instructions and the a3rig://mission resource), the dialogue so far
// (a3rig://dialogue), a tool call's result made from its observation, and the supervisor's
// reply that answers report_turn. Pure functions; mcp_agent.hpp does the waiting.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "agent/conversation/turn.hpp"
#include "agent/mcp/mcp_rig.hpp"
#include "agent/mission/mission.hpp"

namespace a3::agent::mcp {

// What the client is told of its mission (no hidden targets).
struct McpMissionBrief {
  std::string scenario;             // e.g. "parcel-delivery"
  Mission mission;
  nlohmann::json initial_state;     // the scenario's α³-Bench initial_state
  nlohmann::json airspace;          // no-fly zones, traffic, geofence
  int min_turns = 8;
  int max_turns = 12;
};

// a3rig://mission: {scenario, mission, airspace, initial_state, dialogue: {min_turns, max_turns}}.
nlohmann::json mission_resource_json(const McpMissionBrief& brief);
// The InitializeResult's instructions: the role, how calls and turns work, the rules, and the
// mission resource's JSON.
std::string instructions_text(const McpMissionBrief& brief);
// a3rig://dialogue: {"turns": [α³ turn + "text"], "over": bool, "reason"}.
nlohmann::json dialogue_json(const std::vector<Turn>& dialogue, bool over, const std::string& why);

// A vehicle tool's or A2A task's result from its observation: structured = the MCP tool's
// result object (an A2A observation whole); is_error for error, refused (the safety gate or
// the flight controller), failed, rejected and timeout.
McpCallResult observation_result(const nlohmann::json& action, const nlohmann::json& observation);
// report_turn's result: the supervisor's turn (turn, intent, text, net, its actions and
// observations when it had any), the turns left, and whether the dialogue is over.
McpCallResult supervisor_reply_result(const Turn& user_turn, int max_turns, bool dialogue_over, const std::string& why);
// An is_error result: {"status": status, "error": message}.
McpCallResult error_result(const std::string& status, const std::string& message);

}  // namespace a3::agent::mcp
