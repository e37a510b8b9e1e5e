// The mission brief, the dialogue and call results as an MCP client reads them.
#include "agent/mcp/mcp_brief.hpp"

#include <set>

namespace a3::agent::mcp {

nlohmann::json mission_resource_json(const McpMissionBrief& b) {
  nlohmann::json mission = mission_brief_json(b.mission);
  mission["description"] = b.mission.description;
  mission["home_m"] = {b.mission.home_W_m.x(), b.mission.home_W_m.y(), b.mission.home_W_m.z()};
  mission["cruise_altitude_m"] = b.mission.cruise_altitude_m;
  mission["cruise_speed_mps"] = b.mission.cruise_speed_mps;
  mission["time_limit_s"] = b.mission.time_limit_s;
  return {{"scenario", b.scenario},
          {"mission", mission},
          {"airspace", b.airspace},
          {"initial_state", b.initial_state},
          {"dialogue", {{"min_turns", b.min_turns}, {"max_turns", b.max_turns}, {"agent_turns", "odd (1, 3, 5, ...)"}}}};
}

std::string instructions_text(const McpMissionBrief& b) {
  return "You are the autonomous agent of a UAV on the a3rig co-simulation rig (scenario " + b.scenario +
         "), working for a human supervisor over an emulated 6G link.\n"
         "Mission: " + b.mission.description + "\n\n"
         "How it works:\n"
         "- Act only through the tools: the vehicle's MCP tools and the peers' A2A tasks (a2a_<task>). Call them one "
         "at a time; each call crosses the emulated link both ways and executes on the vehicle; its result is the "
         "observation (isError for refusals by the safety gate or the flight controller, errors and timeouts).\n"
         "- End each of your turns with report_turn {intent, text}: it is the turn boundary of the episode, and its "
         "result is the supervisor's reply (the next turn), which comes when the vehicle has settled, an objective "
         "is done, the link degrades or traffic comes close.\n"
         "- The dialogue has " + std::to_string(b.min_turns) + " to " + std::to_string(b.max_turns) +
         " turns; yours are the odd ones. Take off, do every objective, return home and land before the turns run "
         "out. Time passes in the simulated world while you think.\n"
         "- Rules: stay inside the geofence and out of no-fly zones, keep separation from other traffic (negotiate "
         "over A2A), mind the battery, and adapt to the network (e.g. a URLLC slice for control on a bad link).\n"
         "Resources: a3rig://mission (this brief as JSON), a3rig://dialogue (the dialogue so far).\n\n"
         "The mission as JSON:\n" + mission_resource_json(b).dump(2);
}

nlohmann::json dialogue_json(const std::vector<Turn>& dialogue, bool over, const std::string& why) {
  nlohmann::json turns = nlohmann::json::array();
  for (const Turn& t : dialogue) {
    nlohmann::json j = t.to_json();
    j["text"] = t.text;
    turns.push_back(std::move(j));
  }
  return {{"turns", turns}, {"over", over}, {"reason", why}};
}

McpCallResult observation_result(const nlohmann::json& action, const nlohmann::json& observation) {
  static const std::set<std::string> kErrorStatuses = {"error", "refused", "failed", "rejected", "timeout"};
  McpCallResult r;
  if (!observation.is_object()) return error_result("missing", "no observation came back for the call");
  const bool is_tool = action.value("type", "") == "mcp";
  if (is_tool && observation.contains("result") && observation["result"].is_object()) {
    r.structured = observation["result"];
  } else {
    r.structured = observation;
  }
  r.is_error = kErrorStatuses.count(r.structured.value("status", "")) > 0;
  return r;
}

McpCallResult supervisor_reply_result(const Turn& u, int max_turns, bool over, const std::string& why) {
  McpCallResult r;
  r.structured = {{"turn", u.number},
                  {"speaker", u.speaker},
                  {"intent", u.intent},
                  {"text", u.text},
                  {"net", u.net},
                  {"mission_time_s", u.finished_s},
                  {"turns_left", std::max(0, max_turns - u.number)},
                  {"dialogue_over", over}};
  if (!u.actions.empty()) {
    r.structured["actions"] = u.actions;
    r.structured["obs"] = u.obs;
  }
  if (over) r.structured["reason"] = why;
  r.text = "supervisor (turn " + std::to_string(u.number) + ", " + u.intent + "): " + u.text +
           (over ? "\n[the dialogue is over: " + why + "]" : "") + "\n" + r.structured.dump();
  return r;
}

McpCallResult error_result(const std::string& status, const std::string& message) {
  McpCallResult r;
  r.structured = {{"status", status}, {"error", message}};
  r.text = message;
  r.is_error = true;
  return r;
}

}  // namespace a3::agent::mcp
