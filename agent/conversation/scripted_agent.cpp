// The reference policy.
#include "agent/conversation/scripted_agent.hpp"

#include <algorithm>
#include <cmath>

namespace a3::agent {
namespace {

// Telemetry within these of the commanded altitude and speed counts as "at rest there".
constexpr double kAltitudeTolerance_m = 3.0;
constexpr double kRestSpeed_mps = 1.0;
// Telemetry above this height (armed) shows the vehicle has taken off.
constexpr double kAirborneAbove_m = 1.0;

nlohmann::json mcp(const std::string& name, nlohmann::json args = nlohmann::json::object()) {
  return {{"type", "mcp"}, {"name", name}, {"args", std::move(args)}};
}

nlohmann::json a2a(const std::string& task, const std::string& to, nlohmann::json payload = nlohmann::json::object()) {
  return {{"type", "a2a"}, {"task", task}, {"to", to}, {"payload", std::move(payload)}};
}

bool has_traffic(const AgentContext& c) { return c.airspace.contains("traffic") && !c.airspace["traffic"].empty(); }

bool asks_for_separation(const std::vector<nlohmann::json>& actions) {
  return std::any_of(actions.begin(), actions.end(),
                     [](const nlohmann::json& a) { return a.value("task", "") == "collision_avoidance"; });
}

bool landed(const AgentContext& c) {
  return std::any_of(c.dialogue->begin(), c.dialogue->end(), [](const Turn& t) { return t.intent == "acknowledge_landing"; });
}

// With other aircraft about, every turn in the air checks the way ahead with the swarm (after
// any motion, so the swarm predicts along the new route; holding too, as a peer may come back
// past) rather than only when the supervisor reports traffic close by: by then a conflict may
// be seconds away, or the dialogue's last turn.
void check_way_ahead_with_swarm(const AgentContext& c, std::vector<nlohmann::json>* actions) {
  if (!has_traffic(c) || landed(c) || asks_for_separation(*actions)) return;
  actions->push_back(a2a("collision_avoidance", "uav_swarm_agent", {{"intent", "the way ahead"}, {"request", "yield"}}));
}

nlohmann::json polygon_json(const common::Polygon2d& poly) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : poly) out.push_back({p.x(), p.y()});
  return out;
}

double number(const nlohmann::json& j, const char* key, double fallback) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

bool is_motion(const nlohmann::json& action) {
  const std::string name = action.value("name", "");
  return name == "takeoff" || name == "set_waypoint" || name == "navigate_to" || name == "execute_maneuver" ||
         name == "return_to_home";
}

// Where an objective's work starts (for planning a route to it).
Eigen::Vector2d objective_anchor(const Objective& o) {
  if (o.type == ObjectiveType::kSurvey || o.type == ObjectiveType::kThermalSearch) {
    return o.area.empty() ? o.point : o.area.front();
  }
  return o.point;
}

ScriptedAgent::Leg area_leg(const Objective& o) {
  ScriptedAgent::Leg leg;
  const bool thermal = o.type == ObjectiveType::kThermalSearch;
  const std::string sensor = thermal ? "thermal" : o.sensor;
  if (sensor != "rgb") leg.actions.push_back(mcp("activate_sensor", {{"sensor", sensor}}));
  const double spacing = thermal ? std::max(10.0, 1.6 * o.radius_m) : 30.0;
  leg.actions.push_back(mcp("execute_maneuver", {{"maneuver", "survey"},
                                                 {"area", polygon_json(o.area)},
                                                 {"z", o.altitude_m},
                                                 {"spacing_m", spacing},
                                                 {"capture", true},
                                                 {"sensor", sensor}}));
  leg.intent = thermal ? "thermal_search" : "area_survey";
  leg.text = thermal ? "Searching " + o.id + " with the thermal camera." : "Surveying " + o.id + ".";
  leg.ends_at_point = false;
  leg.end_W_m = Eigen::Vector3d(objective_anchor(o).x(), objective_anchor(o).y(), o.altitude_m);
  leg.anchor_W_m = leg.end_W_m;
  return leg;
}

ScriptedAgent::Leg image_leg(const Objective& o) {
  ScriptedAgent::Leg leg;
  // The sensor is switched on with the flight there, so a lost activation is known (and made
  // good) before the capture, not by a failed capture.
  if (o.sensor != "rgb") leg.actions.push_back(mcp("activate_sensor", {{"sensor", o.sensor}}));
  leg.actions.push_back(mcp("set_waypoint", {{"x", o.point.x()}, {"y", o.point.y()}, {"z", o.altitude_m}}));
  leg.intent = "navigate_to_target";
  leg.text = "Flying to " + o.id + " to image it.";
  leg.end_W_m = Eigen::Vector3d(o.point.x(), o.point.y(), o.altitude_m);
  leg.anchor_W_m = leg.end_W_m;
  leg.capture = true;
  leg.capture_actions.push_back(mcp("capture_image", {{"sensor", o.sensor}}));
  leg.capture_intent = "capture_target";
  leg.capture_text = "At " + o.id + ", settled at the commanded altitude: capturing it.";
  return leg;
}

ScriptedAgent::Leg delivery_leg(const Objective& o, double cruise_z_m) {
  ScriptedAgent::Leg leg;
  const double drop_z_m = std::max(2.0, o.drop_altitude_m - 3.0);
  leg.actions.push_back(mcp("navigate_to", {{"waypoints",
                                             {{o.point.x(), o.point.y(), cruise_z_m},
                                              {o.point.x(), o.point.y(), drop_z_m}}}}));
  leg.intent = "deliver_package";
  leg.text = "Flying the parcel to " + o.id + " and descending to drop it.";
  leg.end_W_m = Eigen::Vector3d(o.point.x(), o.point.y(), drop_z_m);
  leg.anchor_W_m = Eigen::Vector3d(o.point.x(), o.point.y(), cruise_z_m);
  return leg;
}

// The turn at dialogue index i, if it is in the dialogue yet.
const Turn* turn_at(const AgentContext& c, int i) {
  return i >= 0 && i < static_cast<int>(c.dialogue->size()) ? &(*c.dialogue)[i] : nullptr;
}

bool failed(const std::string& status) { return status == "refused" || status == "error" || status == "timeout"; }

// "accepted" when every motion command of the turn was, else the first refusal ("refused",
// "error") or loss ("timeout", no answer).
std::string motion_answer(const Turn& t) {
  for (std::size_t i = 0; i < t.actions.size(); ++i) {
    if (!is_motion(t.actions[i])) continue;
    const std::string status = t.answer_status(i);
    if (failed(status)) return status;
  }
  return "accepted";
}

// The first failed answer among the turn's actions named `names`: "<name> timed out" (lost, or
// no answer), "<name>: <error>" for an error or refusal; empty when they all stood.
std::string first_failure(const Turn& t, const std::vector<std::string>& names) {
  for (std::size_t i = 0; i < t.actions.size(); ++i) {
    const std::string name = t.actions[i].value("name", "");
    if (std::find(names.begin(), names.end(), name) == names.end()) continue;
    const std::string status = t.answer_status(i);
    if (status == "timeout") return name + " timed out";
    if (!failed(status)) continue;
    const nlohmann::json& o = t.obs[i];  // answered, so present
    const nlohmann::json& answer = o.contains("result") ? o["result"] : o;
    const bool said = answer.contains("error") && answer["error"].is_string();
    return name + ": " + (said ? answer["error"].get<std::string>() : status);
  }
  return "";
}

// The first failed answer to the sensor actions of a capture turn (activate_sensor, capture_image).
std::string capture_failure(const Turn& t) { return first_failure(t, {"activate_sensor", "capture_image"}); }

bool capture_failed(const Turn& t) { return !capture_failure(t).empty(); }

// The waypoints of the newest ground-station route asked for to `goal` (horizontally), or empty.
std::vector<nlohmann::json> planned_route_to(const AgentContext& c, const Eigen::Vector2d& goal) {
  std::vector<nlohmann::json> route;
  for (const Turn& t : *c.dialogue) {
    for (std::size_t i = 0; i < t.actions.size() && i < t.obs.size(); ++i) {
      const nlohmann::json& a = t.actions[i];
      const nlohmann::json& o = t.obs[i];
      if (a.value("task", "") != "path_plan" || !o.is_object() || o.value("status", "") != "ok") continue;
      const nlohmann::json asked = a.contains("payload") ? a["payload"].value("goal", nlohmann::json()) : nullptr;
      if (!asked.is_array() || asked.size() < 2 || !asked[0].is_number() || !asked[1].is_number()) continue;
      if ((Eigen::Vector2d(asked[0].get<double>(), asked[1].get<double>()) - goal).norm() > 1.0) continue;
      const nlohmann::json w = o.contains("payload") ? o["payload"].value("waypoints", nlohmann::json()) : nullptr;
      if (w.is_array() && !w.empty()) route.assign(w.begin(), w.end());
    }
  }
  return route;
}

// The newest read_telemetry result of the turns after index `after`, or null; *turn_index: its turn.
const nlohmann::json* telemetry_after(const AgentContext& c, int after, int* turn_index) {
  for (int i = static_cast<int>(c.dialogue->size()) - 1; i > after; --i) {
    const Turn& t = (*c.dialogue)[i];
    for (auto o = t.obs.rbegin(); o != t.obs.rend(); ++o) {
      if (o->is_object() && o->value("tool", "") == "read_telemetry" && o->contains("result") &&
          (*o)["result"].is_object() && (*o)["result"].contains("pose")) {
        *turn_index = i;
        return &(*o)["result"];
      }
    }
  }
  return nullptr;
}

// The supervisor has confirmed the objective done ("Confirmed: a, b done.") after index `after`.
bool supervisor_confirmed(const AgentContext& c, int after, const std::string& id) {
  const std::string prefix = "Confirmed: ";
  for (int i = after + 1; i < static_cast<int>(c.dialogue->size()); ++i) {
    const Turn& t = (*c.dialogue)[i];
    if (t.speaker != "user" || t.intent != "acknowledge_progress" || t.text.rfind(prefix, 0) != 0) continue;
    const std::size_t end = t.text.find(" done.");
    std::string names = t.text.substr(prefix.size(), end == std::string::npos ? std::string::npos : end - prefix.size());
    for (std::size_t start = 0; start <= names.size();) {
      const std::size_t comma = names.find(", ", start);
      if (names.substr(start, comma == std::string::npos ? std::string::npos : comma - start) == id) return true;
      if (comma == std::string::npos) break;
      start = comma + 2;
    }
  }
  return false;
}

// The supervisor's latest turn asks for status or confirms the start: it speaks so only once the
// vehicle has come to rest (or after a long silence), not for an objective, a link or traffic.
bool supervisor_saw_rest(const AgentContext& c) {
  if (c.dialogue->empty()) return false;
  const Turn& t = c.dialogue->back();
  return t.speaker == "user" && (t.intent == "request_status" || t.intent == "confirm_mission_start");
}

// The take-off sent in the turn at `launch_turn_index` was not confirmed (lost, refused) and no
// telemetry since shows the vehicle armed and off the ground: it has to be sent again.
bool launch_unconfirmed(const AgentContext& c, int launch_turn_index) {
  const Turn* sent = turn_at(c, launch_turn_index);
  if (sent == nullptr || first_failure(*sent, {"takeoff"}).empty()) return false;
  int tel_turn = -1;
  const nlohmann::json* tel = telemetry_after(c, launch_turn_index, &tel_turn);
  const bool armed = tel != nullptr && tel->contains("armed") && (*tel)["armed"].is_boolean() && (*tel)["armed"].get<bool>();
  return !(armed && number((*tel)["pose"], "z", 0.0) > kAirborneAbove_m);
}

ScriptedAgent::LegStatus status_from_telemetry(const nlohmann::json& tel, const ScriptedAgent::Leg& leg) {
  const std::string mode = tel.value("mode", "");
  const bool on_route = tel.contains("route") && tel["route"].is_object();
  if (mode == "goto" || mode == "takeoff" || on_route) return ScriptedAgent::LegStatus::kFlying;
  if (mode != "hold") return ScriptedAgent::LegStatus::kLost;
  if (!leg.ends_at_point) return ScriptedAgent::LegStatus::kDone;
  const Eigen::Vector2d p(number(tel["pose"], "x", 1e9), number(tel["pose"], "y", 1e9));
  const double z_m = number(tel["pose"], "z", -1e9);
  const double within_m = leg.capture ? leg.radius_m : std::max(leg.radius_m, 5.0);
  const bool there = (p - leg.end_W_m.head<2>()).norm() <= within_m &&
                     std::abs(z_m - leg.end_W_m.z()) <= kAltitudeTolerance_m &&
                     number(tel, "speed_mps", 1e9) <= kRestSpeed_mps;
  return there ? ScriptedAgent::LegStatus::kDone : ScriptedAgent::LegStatus::kLost;
}

}  // namespace

bool is_hard_network(const nlohmann::json& net) {
  return number(net, "lat_ms", 0) > 40 || number(net, "loss_pct", 0) >= 1 || number(net, "throughput_mbps", 1e9) < 5 ||
         number(net, "edge_load", 0) > 0.8;
}

ScriptedAgent::LegStatus leg_status(const AgentContext& c, const ScriptedAgent::Leg& leg, int leg_turn_index) {
  const Turn* sent = turn_at(c, leg_turn_index);
  if (sent == nullptr) return ScriptedAgent::LegStatus::kUnknown;
  const std::string answer = motion_answer(*sent);
  if (answer == "refused" || answer == "error") return ScriptedAgent::LegStatus::kRefused;
  if (answer != "accepted") return ScriptedAgent::LegStatus::kLost;
  if (!leg.capture && supervisor_confirmed(c, leg_turn_index, leg.objective_id)) return ScriptedAgent::LegStatus::kDone;
  // The newest evidence decides: telemetry of the supervisor's latest turn, else the supervisor's
  // word that the vehicle has come to rest since, else older telemetry.
  int tel_turn = -1;
  const nlohmann::json* tel = telemetry_after(c, leg_turn_index, &tel_turn);
  const bool latest = tel != nullptr && tel_turn == static_cast<int>(c.dialogue->size()) - 1;
  if (latest) return status_from_telemetry(*tel, leg);
  if (supervisor_saw_rest(c)) return ScriptedAgent::LegStatus::kDone;
  return tel != nullptr ? status_from_telemetry(*tel, leg) : ScriptedAgent::LegStatus::kUnknown;
}

void ScriptedAgent::plan(const AgentContext& c) {
  const Mission& m = *c.mission;
  for (const auto& o : m.objectives) {
    Leg leg;
    switch (o.type) {
      case ObjectiveType::kSurvey:
      case ObjectiveType::kThermalSearch: leg = area_leg(o); break;
      case ObjectiveType::kImagePoint: leg = image_leg(o); break;
      case ObjectiveType::kDelivery: leg = delivery_leg(o, m.cruise_altitude_m); break;
      case ObjectiveType::kReturnAndLand: continue;
    }
    leg.objective_id = o.id;
    leg.radius_m = o.radius_m;
    legs_.push_back(std::move(leg));
  }
  preflight_ = {"preflight_check", "Checking telemetry, geofence and weather before launch.", {}};
  preflight_.actions.push_back(mcp("read_telemetry"));
  preflight_.actions.push_back(mcp("check_geofence"));
  preflight_.actions.push_back(a2a("request_weather_update", "weather_service"));
  const bool has_zones = c.airspace.contains("no_fly_zones") && !c.airspace["no_fly_zones"].empty();
  const auto first = std::find_if(m.objectives.begin(), m.objectives.end(),
                                  [](const Objective& o) { return o.type != ObjectiveType::kReturnAndLand; });
  if (has_zones && first != m.objectives.end()) {
    const Eigen::Vector2d goal = objective_anchor(*first);
    preflight_.actions.push_back(a2a("path_plan", "ground_station",
                                     {{"start", {m.home_W_m.x(), m.home_W_m.y()}},
                                      {"goal", {goal.x(), goal.y()}},
                                      {"z", m.cruise_altitude_m}}));
  }
  if (has_traffic(c)) {
    preflight_.actions.push_back(a2a("swarm_status_check", "uav_swarm_agent"));
  }
}

int ScriptedAgent::turns_needed_after_preflight() const {
  int turns = 0;
  bool after_capture = false;
  for (std::size_t i = leg_; i < legs_.size(); ++i) {
    // A leg's motion takes a turn of its own, or rides on the capture before it and then needs
    // a check on the way (the supervisor acknowledges that capture at once).
    if (!(i == leg_ && leg_sent_)) ++turns;
    if (legs_[i].capture) ++turns;
    after_capture = legs_[i].capture;
  }
  if (!returned_ && !after_capture) ++turns;  // the return rides on a last capture
  return turns;
}

std::vector<nlohmann::json> ScriptedAgent::route_for(const AgentContext& c, const Leg& leg,
                                                     const nlohmann::json& motion) const {
  std::vector<nlohmann::json> route = planned_route_to(c, leg.anchor_W_m.head<2>());
  if (route.empty()) return route;
  // The planner's detour, ending with the leg's own waypoints: its target altitude, its descent.
  const std::string name = motion.value("name", "");
  const nlohmann::json& args = motion["args"];
  if (name == "set_waypoint") {
    route.back() = {args["x"], args["y"], args["z"]};
  } else if (name == "navigate_to") {
    const nlohmann::json& own = args["waypoints"];
    route.back() = own.front();
    for (std::size_t i = 1; i < own.size(); ++i) route.push_back(own[i]);
  } else {
    route.clear();
  }
  return route;
}

void ScriptedAgent::put_transit_before_pattern(const AgentContext& c) {
  // A pattern (survey) cannot follow a route itself: fly the route to its start first.
  Leg& pattern = legs_[leg_];
  if (pattern.ends_at_point || pattern.transit_planned) return;
  std::vector<nlohmann::json> route = planned_route_to(c, pattern.anchor_W_m.head<2>());
  if (route.empty()) return;
  pattern.transit_planned = true;
  Leg transit;
  transit.objective_id = pattern.objective_id + "-transit";
  transit.intent = "navigate_around_no_fly_zone";
  transit.text = "Flying the ground station's route around the no-fly zone to " + pattern.objective_id + ".";
  route.back() = {pattern.anchor_W_m.x(), pattern.anchor_W_m.y(), pattern.anchor_W_m.z()};
  transit.actions.push_back(mcp("navigate_to", {{"waypoints", route}}));
  transit.end_W_m = pattern.anchor_W_m;
  transit.anchor_W_m = pattern.anchor_W_m;
  transit.radius_m = 10.0;
  transit.is_route = true;
  legs_.insert(legs_.begin() + static_cast<std::ptrdiff_t>(leg_), std::move(transit));
}

void ScriptedAgent::add_leg_motion(const AgentContext& c, Choice* choice) {
  put_transit_before_pattern(c);
  Leg& leg = legs_[leg_];
  ++leg.sends;
  if (!launched_ || launch_unconfirmed(c, launch_turn_index_)) {
    choice->actions.push_back(mcp("takeoff", {{"altitude_m", c.mission->cruise_altitude_m}}));
    launched_ = true;
    launch_turn_index_ = static_cast<int>(c.dialogue->size());
  }
  for (const auto& a : leg.actions) {
    auto route = is_motion(a) && !leg.is_route ? route_for(c, leg, a) : std::vector<nlohmann::json>{};
    choice->actions.push_back(route.empty() ? a : mcp("navigate_to", {{"waypoints", route}}));
  }
  choice->intent += (choice->intent.empty() ? "" : "+") + leg.intent;
  choice->text += (choice->text.empty() ? "" : " ") + leg.text;
  leg_sent_ = true;
  leg_turn_index_ = static_cast<int>(c.dialogue->size());
}

void ScriptedAgent::add_return(const AgentContext& c, Choice* choice) {
  choice->actions.push_back(mcp("return_to_home"));
  choice->intent += std::string(choice->intent.empty() ? "" : "+") + "return_to_home";
  // Say what is left undone rather than claim the mission done: objectives given up, a capture
  // that failed, and every leg not reached.
  std::vector<std::string> undone = given_up_;
  for (std::size_t i = leg_; i < legs_.size(); ++i) {
    if (!legs_[i].is_route) undone.push_back(legs_[i].objective_id);
  }
  std::string list;
  for (const auto& id : undone) list += (list.empty() ? "" : ", ") + id;
  choice->text += std::string(choice->text.empty() ? "" : " ") +
                  (undone.empty() ? "Mission tasks done: returning home to land." : "Returning home to land; not done: " + list + ".");
  returned_ = true;
  return_turn_index_ = static_cast<int>(c.dialogue->size());
}

ScriptedAgent::Choice ScriptedAgent::preflight_choice(const AgentContext& c) {
  const int agent_turns_left = (c.max_turns - c.turn_number) / 2 + 1;
  Choice choice = preflight_;
  preflight_done_ = true;
  // Short of turns: launch with the pre-flight, onto the first leg.
  if (!legs_.empty() && 1 + turns_needed_after_preflight() > agent_turns_left) add_leg_motion(c, &choice);
  return choice;
}

ScriptedAgent::Choice ScriptedAgent::after_leg_done(const AgentContext& c, int agent_turns_left) {
  Choice choice;
  Leg& done = legs_[leg_];
  if (done.capture) {
    choice = {done.capture_intent, done.capture_text, done.capture_actions};
    // Its sensor's activation, sent with the leg, was not confirmed: activate it again first.
    const Turn* sent = turn_at(c, leg_turn_index_);
    if (sent != nullptr && !first_failure(*sent, {"activate_sensor"}).empty()) {
      for (const auto& a : done.actions) {
        if (a.value("name", "") == "activate_sensor") choice.actions.insert(choice.actions.begin(), a);
      }
    }
    ++done.captures;
    capture_turn_index_ = static_cast<int>(c.dialogue->size());
    captured_leg_ = leg_;
  }
  ++leg_;
  leg_sent_ = false;
  // Capture first, then move on: the next leg, or home when there is none or no turn after this.
  if (leg_ < legs_.size() && agent_turns_left > 1) {
    add_leg_motion(c, &choice);
  } else {
    add_return(c, &choice);
  }
  return choice;
}

ScriptedAgent::Choice ScriptedAgent::after_refusal(const AgentContext& c, int agent_turns_left) {
  const Leg& leg = legs_[leg_];
  const bool has_zones = c.airspace.contains("no_fly_zones") && !c.airspace["no_fly_zones"].empty();
  leg_sent_ = false;
  const Turn* sent = turn_at(c, leg_turn_index_);
  const std::string setup = sent == nullptr ? "" : first_failure(*sent, {"activate_sensor"});
  if (!setup.empty() && leg.sends < 3) {
    // Refused for want of its sensor (the activation lost or failed): set it up again with the leg.
    Choice choice{"", "The leg to " + leg.objective_id + " was not flown (" + setup + "); activating the sensor again with it.", {}};
    add_leg_motion(c, &choice);
    return choice;
  }
  if (has_zones && leg.sends < 3 && planned_route_to(c, leg.anchor_W_m.head<2>()).empty()) {
    // Refused on the way (a no-fly zone): ask the ground station for a route from here; the
    // next turn flies the leg along it.
    return {"request_route", "The gate refused the direct leg to " + leg.objective_id + "; asking for a route around.",
            {a2a("path_plan", "ground_station",
                 {{"goal", {leg.anchor_W_m.x(), leg.anchor_W_m.y()}}, {"z", leg.anchor_W_m.z()}})}};
  }
  if (leg.sends < 3) {
    Choice choice{"", "The gate refused the last leg; sending it along the planned route.", {}};
    add_leg_motion(c, &choice);
    return choice;
  }
  // Refused again and again: give this objective up and go on with the next.
  if (!leg.is_route) given_up_.push_back(leg.objective_id);
  ++leg_;
  Choice choice{"", "The gate keeps refusing " + leg.objective_id + "; moving on.", {}};
  if (leg_ < legs_.size() && agent_turns_left > 1) {
    add_leg_motion(c, &choice);
  } else {
    add_return(c, &choice);
  }
  return choice;
}

std::optional<ScriptedAgent::Choice> ScriptedAgent::retake_failed_capture(const AgentContext& c, int agent_turns_left) {
  const Turn* sent = turn_at(c, capture_turn_index_);
  if (sent == nullptr || !capture_failed(*sent) || returned_) return std::nullopt;
  Leg& leg = legs_[captured_leg_];
  // Only the answer was lost if the supervisor has confirmed the objective since: it stands.
  if (supervisor_confirmed(c, capture_turn_index_, leg.objective_id)) return std::nullopt;
  capture_turn_index_ = -1;
  // Back to the point, then the capture there with the way home: two agent turns at least.
  if (leg.captures >= 2 || agent_turns_left < 2) {
    given_up_.push_back(leg.objective_id);  // the capture failed and cannot be taken again
    return std::nullopt;
  }
  leg_ = captured_leg_;
  leg.sends = 0;
  Choice choice{"", "The capture at " + leg.objective_id + " was not confirmed (" + capture_failure(*sent) +
                        "); flying back to take it again.", {}};
  add_leg_motion(c, &choice);
  return choice;
}

ScriptedAgent::Choice ScriptedAgent::next_choice(const AgentContext& c) {
  const int agent_turns_left = (c.max_turns - c.turn_number) / 2 + 1;
  if (!preflight_done_) return preflight_choice(c);
  if (returned_) {
    const Turn* sent = turn_at(c, return_turn_index_);
    if (sent != nullptr && motion_answer(*sent) != "accepted") {
      // The return was lost or not confirmed on a poor link: send it again.
      Choice again{"", "The return command was not confirmed; sending it again.", {}};
      add_return(c, &again);
      return again;
    }
    const bool first_after = !c.dialogue->empty() && c.dialogue->back().intent == "acknowledge_landing";
    return {first_after ? "confirm_landing" : "status_report",
            first_after ? "Confirming the landing." : "Reporting status.", {mcp("read_telemetry")}};
  }
  if (auto retake = retake_failed_capture(c, agent_turns_left)) return *retake;
  Choice choice;
  if (leg_ >= legs_.size()) {
    add_return(c, &choice);
    return choice;
  }
  if (!leg_sent_) {
    add_leg_motion(c, &choice);
    return choice;
  }
  switch (leg_status(c, legs_[leg_], leg_turn_index_)) {
    case LegStatus::kDone:
      return after_leg_done(c, agent_turns_left);
    case LegStatus::kRefused:
      if (agent_turns_left > 1) return after_refusal(c, agent_turns_left);
      break;
    case LegStatus::kLost:
      if (agent_turns_left > 1 && legs_[leg_].sends < 3) {
        choice = {"", "The last leg did not get there; sending it again.", {}};
        add_leg_motion(c, &choice);
        return choice;
      }
      break;
    case LegStatus::kFlying:
    case LegStatus::kUnknown:
      if (agent_turns_left > 1) return {"monitor_progress", "The current leg is not confirmed done; checking position.", {mcp("read_telemetry")}};
      break;
  }
  // The last turn, the leg unfinished: come home rather than stay out.
  add_return(c, &choice);
  return choice;
}

std::vector<nlohmann::json> ScriptedAgent::adapt_to_network(const AgentContext& c, std::vector<nlohmann::json> actions) {
  // URLLC for control on a hard link; images stay on board until it is good.
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
  return adapted;
}

AgentDecision ScriptedAgent::decide(const AgentContext& c) {
  if (!planned_) {
    plan(c);
    planned_ = true;
  }
  Choice choice = next_choice(c);
  if (launched_) check_way_ahead_with_swarm(c, &choice.actions);
  // Traffic reported close by the supervisor: negotiate separation first.
  if (!c.dialogue->empty() && c.dialogue->back().speaker == "user" && c.dialogue->back().intent == "traffic_alert" &&
      !asks_for_separation(choice.actions)) {
    choice.actions.insert(choice.actions.begin(), a2a("collision_avoidance", "uav_swarm_agent",
                                                      {{"intent", "hold position for the mission"}, {"request", "yield"}}));
  }
  AgentDecision d;
  d.intent = choice.intent.empty() ? "resend_leg" : choice.intent;
  d.text = choice.text;
  d.actions = nlohmann::json(adapt_to_network(c, std::move(choice.actions)));
  return d;
}

}  // namespace a3::agent
