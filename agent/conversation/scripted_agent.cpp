// The reference policy.
#include "agent/conversation/scripted_agent.hpp"

#include <cmath>

namespace a3::agent {
namespace {

nlohmann::json mcp(const std::string& name, nlohmann::json args = nlohmann::json::object()) {
  return {{"type", "mcp"}, {"name", name}, {"args", std::move(args)}};
}

nlohmann::json a2a(const std::string& task, const std::string& to, nlohmann::json payload = nlohmann::json::object()) {
  return {{"type", "a2a"}, {"task", task}, {"to", to}, {"payload", std::move(payload)}};
}

nlohmann::json polygon_json(const common::Polygon2d& poly) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : poly) out.push_back({p.x(), p.y()});
  return out;
}

double number(const nlohmann::json& j, const char* key, double fallback) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

// Where an objective's work starts (for planning a route to it).
Eigen::Vector2d objective_anchor(const Objective& o) {
  if (o.type == ObjectiveType::kSurvey || o.type == ObjectiveType::kThermalSearch) {
    return o.area.empty() ? o.point : o.area.front();
  }
  return o.point;
}

}  // namespace

bool ScriptedAgent::still_flying_a_route(const AgentContext& c) const {
  // The newest telemetry in the dialogue: moving on a route or toward a target.
  for (auto t = c.dialogue->rbegin(); t != c.dialogue->rend(); ++t) {
    for (const auto& o : t->obs) {
      if (o.is_object() && o.value("tool", "") == "read_telemetry" && o.contains("result") && o["result"].is_object()) {
        const auto& r = o["result"];
        const std::string mode = r.value("mode", "");
        return (mode == "goto" || mode == "takeoff") && r.contains("route") && r["route"].is_object();
      }
    }
  }
  return false;
}

bool is_hard_network(const nlohmann::json& net) {
  return number(net, "lat_ms", 0) > 40 || number(net, "loss_pct", 0) >= 1 || number(net, "throughput_mbps", 1e9) < 5 ||
         number(net, "edge_load", 0) > 0.8;
}

std::vector<nlohmann::json> ScriptedAgent::route_from_path_plan(const AgentContext& context) const {
  // The ground station's path_plan answer from the pre-flight turn, if there was one.
  for (const Turn& t : *context.dialogue) {
    for (const auto& o : t.obs) {
      if (o.value("task", "") == "path_plan" && o.value("status", "") == "ok" && o.contains("payload") &&
          o["payload"].contains("waypoints") && o["payload"]["waypoints"].is_array()) {
        std::vector<nlohmann::json> out;
        for (const auto& w : o["payload"]["waypoints"]) out.push_back(w);
        return out;
      }
    }
  }
  return {};
}

void ScriptedAgent::plan(const AgentContext& c) {
  const Mission& m = *c.mission;
  const double z = m.cruise_altitude_m;
  // Turn 1: pre-flight.
  Step pre{"preflight_check", "Checking telemetry, geofence and weather before launch.", {}};
  pre.actions.push_back(mcp("read_telemetry"));
  pre.actions.push_back(mcp("check_geofence"));
  pre.actions.push_back(a2a("request_weather_update", "weather_service"));
  const bool has_zones = c.airspace.contains("no_fly_zones") && !c.airspace["no_fly_zones"].empty();
  const Objective* first_leg = nullptr;
  for (const auto& o : m.objectives) {
    if (o.type != ObjectiveType::kReturnAndLand) {
      first_leg = &o;
      break;
    }
  }
  if (has_zones && first_leg != nullptr) {
    const Eigen::Vector2d goal = objective_anchor(*first_leg);
    pre.actions.push_back(a2a("path_plan", "ground_station",
                              {{"start", {m.home_W_m.x(), m.home_W_m.y()}}, {"goal", {goal.x(), goal.y()}}, {"z", z}}));
  }
  if (c.airspace.contains("traffic") && !c.airspace["traffic"].empty()) {
    pre.actions.push_back(a2a("swarm_status_check", "uav_swarm_agent"));
  }
  steps_.push_back(pre);

  // Take-off, then one turn per objective.
  bool launched = false;
  for (const auto& o : m.objectives) {
    if (o.type == ObjectiveType::kReturnAndLand) continue;
    Step s{"", "", {}};
    if (!launched) {
      s.actions.push_back(mcp("takeoff", {{"altitude_m", z}}));
      launched = true;
    }
    switch (o.type) {
      case ObjectiveType::kSurvey:
      case ObjectiveType::kThermalSearch: {
        const bool thermal = o.type == ObjectiveType::kThermalSearch;
        const std::string sensor = thermal ? "thermal" : o.sensor;
        if (sensor != "rgb") s.actions.push_back(mcp("activate_sensor", {{"sensor", sensor}}));
        const double spacing = thermal ? std::max(10.0, 1.6 * o.radius_m) : 30.0;
        s.actions.push_back(mcp("execute_maneuver", {{"maneuver", "survey"},
                                                     {"area", polygon_json(o.area)},
                                                     {"z", o.altitude_m},
                                                     {"spacing_m", spacing},
                                                     {"capture", true},
                                                     {"sensor", sensor}}));
        s.intent = thermal ? "thermal_search" : "area_survey";
        s.text = thermal ? "Searching " + o.id + " with the thermal camera." : "Surveying " + o.id + ".";
        break;
      }
      case ObjectiveType::kImagePoint:
        s.actions.push_back(mcp("set_waypoint", {{"x", o.point.x()}, {"y", o.point.y()}, {"z", o.altitude_m}}));
        s.intent = "navigate_to_target";
        s.text = "Flying to " + o.id + " to image it.";
        steps_.push_back(s);
        s = Step{"capture_target", "Capturing " + o.id + ".", {}};
        s.needs_arrival = true;
        s.at = o.point;
        s.arrive_within_m = std::max(10.0, 2.0 * o.radius_m);
        if (o.sensor != "rgb") s.actions.push_back(mcp("activate_sensor", {{"sensor", o.sensor}}));
        s.actions.push_back(mcp("capture_image", {{"sensor", o.sensor}}));
        break;
      case ObjectiveType::kDelivery:
        s.actions.push_back(mcp("navigate_to", {{"waypoints",
                                                 {{o.point.x(), o.point.y(), z},
                                                  {o.point.x(), o.point.y(), std::max(2.0, o.drop_altitude_m - 3.0)}}}}));
        s.intent = "deliver_package";
        s.text = "Flying the parcel to " + o.id + " and descending to drop it.";
        break;
      case ObjectiveType::kReturnAndLand:
        break;
    }
    steps_.push_back(s);
  }
  steps_.push_back({"return_to_home", "Mission tasks done: returning home to land.", {mcp("return_to_home")}});
  steps_.push_back({"confirm_landing", "Confirming the landing.", {mcp("read_telemetry")}});
}

bool ScriptedAgent::last_leg_done(const AgentContext& c) const {
  if (leg_turn_index_ < 0) return true;
  const auto& turns = *c.dialogue;
  for (int i = static_cast<int>(turns.size()) - 1; i > leg_turn_index_; --i) {
    for (auto o = turns[i].obs.rbegin(); o != turns[i].obs.rend(); ++o) {
      if (o->is_object() && o->value("tool", "") == "read_telemetry" && o->contains("result") &&
          (*o)["result"].is_object()) {
        const std::string mode = (*o)["result"].value("mode", "");
        return mode != "goto" && mode != "takeoff";
      }
    }
  }
  return false;
}

bool ScriptedAgent::arrived(const AgentContext& c, const Step& step) {
  if (!step.needs_arrival) return true;
  const nlohmann::json& t = c.last_telemetry;
  if (!t.is_object() || !t.contains("pose") || !t["pose"].is_object()) return false;
  const Eigen::Vector2d p(number(t["pose"], "x", 1e9), number(t["pose"], "y", 1e9));
  return (p - step.at).norm() <= step.arrive_within_m;
}

AgentDecision ScriptedAgent::decide(const AgentContext& c) {
  if (!planned_) {
    plan(c);
    planned_ = true;
  }
  AgentDecision d;
  const int agent_turns_left = (c.max_turns - c.turn_number) / 2 + 1;
  Step step;
  if (still_flying_a_route(c) && agent_turns_left > static_cast<int>(steps_.size())) {
    // The last leg is still being flown: check on it rather than start the next one.
    step = {"monitor_progress", "The current leg is still in progress; monitoring.", {mcp("read_telemetry")}};
  } else if (!steps_.empty() && (!last_leg_done(c) || !arrived(c, steps_.front())) &&
             agent_turns_left > static_cast<int>(steps_.size())) {
    // Not at the place of the next step yet (as far as the telemetry says): check on the way.
    step = {"monitor_progress", "The last leg is not confirmed done; checking position.", {mcp("read_telemetry")}};
  } else if (steps_.empty()) {
    step = {"status_report", "Reporting status.", {mcp("read_telemetry")}};
  } else if (static_cast<int>(steps_.size()) > agent_turns_left && steps_.size() >= 3) {
    // Running out of turns: fold the next two steps into one.
    step = steps_.front();
    steps_.pop_front();
    for (auto& a : steps_.front().actions) step.actions.push_back(a);
    step.intent += "+" + steps_.front().intent;
    steps_.pop_front();
  } else {
    step = steps_.front();
    steps_.pop_front();
  }

  // The first leg follows the ground station's route around no-fly zones, if it gave one:
  // the route replaces the motion toward the first objective.
  std::vector<nlohmann::json> actions;
  for (auto& a : step.actions) {
    const std::string name = a.value("name", "");
    auto route = route_from_path_plan(c);
    if (!route.empty() && !detour_flown_ && (name == "set_waypoint" || name == "navigate_to")) {
      detour_flown_ = true;
      if (name == "set_waypoint") {
        route.back() = {a["args"]["x"], a["args"]["y"], a["args"]["z"]};
      }
      actions.push_back(mcp("navigate_to", {{"waypoints", route}}));
      continue;
    }
    // Going home past a no-fly zone needs nothing special: return_to_home plans its own detour
    // on the vehicle and lands at home.
    actions.push_back(a);
  }
  // Traffic reported close by the supervisor: negotiate separation first.
  if (!c.dialogue->empty() && c.dialogue->back().speaker == "user" && c.dialogue->back().intent == "traffic_alert") {
    actions.insert(actions.begin(), a2a("collision_avoidance", "uav_swarm_agent",
                                        {{"intent", "hold position for the mission"}, {"request", "yield"}}));
  }

  // Network adaptation: URLLC for control on a hard link; images stay on board until it is good.
  const bool hard = is_hard_network(c.net);
  const bool slow = number(c.net, "throughput_mbps", 1e9) < 5.0;
  std::vector<nlohmann::json> adapted;
  if (hard && c.net.value("slice", "") != "URLLC") {
    adapted.push_back(mcp("switch_network_slice", {{"slice", "URLLC"}}));
  }
  for (auto& a : actions) {
    if (a.value("name", "") == "capture_image" && slow) {
      a["args"]["store_only"] = true;
      images_held_ = true;
    }
    adapted.push_back(a);
  }
  if (images_held_ && !slow && !hard) {
    adapted.push_back(a2a("handover_data", "ground_station", {{"items", nlohmann::json::array({"held_images"})}}));
    images_held_ = false;
  }
  for (const auto& a : adapted) {
    const std::string name = a.value("name", "");
    if (name == "takeoff" || name == "set_waypoint" || name == "navigate_to" || name == "execute_maneuver") {
      leg_turn_index_ = static_cast<int>(c.dialogue->size());
    }
  }
  d.intent = step.intent;
  d.text = step.text;
  d.actions = nlohmann::json(adapted);
  return d;
}

}  // namespace a3::agent
