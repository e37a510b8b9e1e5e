// The run status the agent's recorded turns call for.
#include "rigs/run/agent_outcome.hpp"

#include <cstdio>

namespace a3::rigs {
namespace {

using nlohmann::json;

bool is_agent_turn(const json& t) { return t.is_object() && t.value("speaker", "") == "agent"; }

bool has_action(const json& t) {
  const auto it = t.find("actions");
  return it != t.end() && it->is_array() && !it->empty();
}

const json& attempt_log(const json& t) {
  static const json kNone = json::array();
  if (!t.contains("_rig") || !t["_rig"].is_object()) return kNone;
  const json& rig = t["_rig"];
  return rig.contains("attempt_log") && rig["attempt_log"].is_array() ? rig["attempt_log"] : kNone;
}

// A turn without actions whose last attempt failed at the endpoint.
bool failed_at_endpoint(const json& t) {
  const json& log = attempt_log(t);
  return !has_action(t) && !log.empty() && log.back().is_object() && log.back().value("endpoint_failure", false);
}

std::string last_error(const json& t) {
  const json& log = attempt_log(t);
  if (log.empty() || !log.back().is_object()) return t.value("text", "");
  const json problems = log.back().value("problems", json::array());
  return problems.is_array() && !problems.empty() && problems.back().is_string() ? problems.back().get<std::string>()
                                                                                  : t.value("text", "");
}

}  // namespace

std::string endpoint_failure_status(const std::vector<json>& turns) {
  int in_a_row = 0;
  const json* last = nullptr;
  for (const json& t : turns) {
    if (!is_agent_turn(t)) continue;
    in_a_row = failed_at_endpoint(t) ? in_a_row + 1 : 0;
    last = &t;
  }
  if (in_a_row < kEndpointFailedTurns || last == nullptr) return "";
  return "endpoint_failed: " + std::to_string(in_a_row) + " agent turns in a row failed at the endpoint; last: " +
         last_error(*last);
}

std::string agent_failure_status(const std::vector<json>& turns) {
  int agent_turns = 0;
  const json* last = nullptr;
  for (const json& t : turns) {
    if (!is_agent_turn(t)) continue;
    if (has_action(t)) return "";
    ++agent_turns;
    last = &t;
  }
  std::string why = "agent_failed: no agent turn had a valid action (" + std::to_string(agent_turns) + " agent turn" +
                    (agent_turns == 1 ? "" : "s");
  if (last != nullptr && !last_error(*last).empty()) why += "; last: " + last_error(*last);
  return why + ")";
}

std::string never_flew_status(bool has_flown, double max_altitude_m, std::size_t objectives) {
  if (has_flown || objectives == 0) return "";
  char highest[32];
  std::snprintf(highest, sizeof highest, "%.2f", max_altitude_m);
  return "never_flew: the vehicle never left the ground (highest " + std::string(highest) + " m) though the mission has " +
         std::to_string(objectives) + " objective" + (objectives == 1 ? "" : "s");
}

}  // namespace a3::rigs
