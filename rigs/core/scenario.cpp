// Scenario files.
#include "rigs/core/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/json_file.hpp"
#include "common/json_text.hpp"
#include "rigs/core/builtin_scenarios.hpp"

namespace a3::rigs {
namespace {

using common::InputError;
using common::number_or;
using common::require_array;
using common::require_number;
using common::require_object;
using common::require_string;

Eigen::Vector2d point2(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() < 2 || !j[0].is_number() || !j[1].is_number()) {
    throw InputError(where + ": expected [x, y] in metres");
  }
  return {j[0].get<double>(), j[1].get<double>()};
}

Eigen::Vector3d point3(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number()) {
    throw InputError(where + ": expected [x, y, z] in metres");
  }
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

common::Polygon2d polygon(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() < 3) throw InputError(where + ": a polygon needs at least 3 [x, y] points");
  common::Polygon2d out;
  for (std::size_t i = 0; i < j.size(); ++i) out.push_back(point2(j[i], where + "/" + std::to_string(i)));
  return out;
}

agent::ObjectiveType objective_type(const std::string& s, const std::string& where) {
  if (s == "survey") return agent::ObjectiveType::kSurvey;
  if (s == "image_point") return agent::ObjectiveType::kImagePoint;
  if (s == "delivery") return agent::ObjectiveType::kDelivery;
  if (s == "thermal_search") return agent::ObjectiveType::kThermalSearch;
  if (s == "return_and_land") return agent::ObjectiveType::kReturnAndLand;
  throw InputError(where + ": unknown objective type '" + s +
                   "' (survey, image_point, delivery, thermal_search, return_and_land)");
}

agent::Objective objective(const nlohmann::json& j, const std::string& w) {
  agent::Objective o;
  o.id = require_string(j, "id", w);
  o.type = objective_type(require_string(j, "type", w), w + "/type");
  o.description = j.value("description", "");
  o.radius_m = number_or(j, "radius_m", o.radius_m, w);
  o.altitude_m = number_or(j, "altitude_m", o.altitude_m, w);
  o.sensor = j.value("sensor", o.type == agent::ObjectiveType::kThermalSearch ? "thermal" : "rgb");
  switch (o.type) {
    case agent::ObjectiveType::kSurvey:
      o.area = polygon(require_array(j, "area", w), w + "/area");
      o.images_required = static_cast<int>(number_or(j, "images_required", o.images_required, w));
      if (o.images_required < 1) throw InputError(w + "/images_required: must be >= 1");
      break;
    case agent::ObjectiveType::kThermalSearch:
      o.area = polygon(require_array(j, "area", w), w + "/area");
      o.hidden_target = point2(j.contains("target") ? j["target"] : nlohmann::json(), w + "/target");
      if (!common::polygon_contains(o.area, o.hidden_target)) throw InputError(w + "/target: must lie inside the area");
      break;
    case agent::ObjectiveType::kImagePoint:
      o.point = point2(j.contains("point") ? j["point"] : nlohmann::json(), w + "/point");
      break;
    case agent::ObjectiveType::kDelivery:
      o.point = point2(j.contains("point") ? j["point"] : nlohmann::json(), w + "/point");
      o.drop_altitude_m = number_or(j, "drop_altitude_m", o.drop_altitude_m, w);
      break;
    case agent::ObjectiveType::kReturnAndLand:
      o.radius_m = number_or(j, "radius_m", 5.0, w);
      break;
  }
  if (!(o.radius_m > 0.0)) throw InputError(w + "/radius_m: must be > 0");
  if (!(o.altitude_m > 0.0)) throw InputError(w + "/altitude_m: must be > 0");
  return o;
}

agent::NoFlyZone no_fly_zone(const nlohmann::json& j, const std::string& w) {
  agent::NoFlyZone z;
  z.id = require_string(j, "id", w);
  const std::string type = require_string(j, "type", w);
  if (type == "cylinder") {
    z.centre = point2(j.contains("center") ? j["center"] : nlohmann::json(), w + "/center");
    z.radius_m = require_number(j, "radius_m", w);
    if (!(z.radius_m > 0.0)) throw InputError(w + "/radius_m: must be > 0");
  } else if (type == "polygon") {
    z.polygon = polygon(require_array(j, "points", w), w + "/points");
  } else {
    throw InputError(w + "/type: '" + type + "' is not cylinder or polygon");
  }
  z.floor_m = number_or(j, "floor_m", 0.0, w);
  z.ceiling_m = number_or(j, "ceiling_m", 1e9, w);
  if (!(z.floor_m < z.ceiling_m)) throw InputError(w + ": floor_m must be below ceiling_m");
  return z;
}

agent::TrafficPlan traffic(const nlohmann::json& j, const std::string& w) {
  agent::TrafficPlan t;
  t.id = require_string(j, "id", w);
  const auto& path = require_array(j, "path", w);
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::string wp = w + "/path/" + std::to_string(i);
    agent::TrafficWaypoint p;
    p.t_s = require_number(path[i], "t_s", wp);
    p.p_W_m = point3(path[i].contains("p") ? path[i]["p"] : nlohmann::json(), wp + "/p");
    if (!t.path.empty() && !(p.t_s > t.path.back().t_s)) throw InputError(wp + "/t_s: times must increase");
    t.path.push_back(p);
  }
  if (t.path.empty()) throw InputError(w + "/path: needs at least one point");
  t.min_separation_m = number_or(j, "min_separation_m", t.min_separation_m, w);
  t.yields_when_asked = j.value("yields_when_asked", true);
  t.yield_climb_m = number_or(j, "yield_climb_m", t.yield_climb_m, w);
  t.conflict_deadline_s = number_or(j, "conflict_deadline_s", 0.0, w);
  return t;
}

void airspace_from_initial_state(const nlohmann::json& state, const std::string& where, agent::Airspace& a) {
  if (!state.contains("airspace")) return;
  const auto& air = require_object(state, "airspace", where);
  if (air.contains("alt_bounds")) {
    const auto& b = require_array(air, "alt_bounds", where + "/airspace");
    if (b.size() != 2 || !b[0].is_number() || !b[1].is_number() || !(b[0].get<double>() < b[1].get<double>())) {
      throw InputError(where + "/airspace/alt_bounds: expected [min, max] with min < max");
    }
    a.min_altitude_m = b[0].get<double>();
    a.max_altitude_m = b[1].get<double>();
  }
  if (air.contains("geofence")) {
    const auto& fences = require_array(air, "geofence", where + "/airspace");
    if (!fences.empty()) {
      a.geofence = polygon(require_array(fences[0], "points", where + "/airspace/geofence/0"),
                           where + "/airspace/geofence/0/points");
    }
  }
}

}  // namespace

nlohmann::json Scenario::airspace_brief() const {
  nlohmann::json zones = nlohmann::json::array();
  for (const auto& z : airspace.no_fly_zones) {
    nlohmann::json j = {{"id", z.id}, {"floor_m", z.floor_m}, {"ceiling_m", z.ceiling_m}};
    if (z.polygon.empty()) {
      j["type"] = "cylinder";
      j["center"] = {z.centre.x(), z.centre.y()};
      j["radius_m"] = z.radius_m;
    } else {
      j["type"] = "polygon";
      j["points"] = nlohmann::json::array();
      for (const auto& p : z.polygon) j["points"].push_back({p.x(), p.y()});
    }
    zones.push_back(j);
  }
  nlohmann::json peers = nlohmann::json::array();
  for (const auto& t : airspace.traffic) {
    peers.push_back({{"id", t.id}, {"min_separation_m", t.min_separation_m}, {"contact", "uav_swarm_agent"}});
  }
  nlohmann::json fence = nlohmann::json::array();
  for (const auto& p : airspace.geofence) fence.push_back({p.x(), p.y()});
  return {{"geofence", fence}, {"alt_bounds", {airspace.min_altitude_m, airspace.max_altitude_m}},
          {"no_fly_zones", zones}, {"traffic", peers}};
}

Scenario scenario_from_json(const nlohmann::json& j, const std::string& where, const std::filesystem::path& base_dir) {
  if (!j.is_object()) throw InputError(where + ": a scenario must be a JSON object");
  Scenario s;
  s.source = where;
  s.name = require_string(j, "name", where);
  s.description = j.value("description", "");
  s.airframe = j.value("airframe", "iris");
  s.initial_state = require_object(j, "initial_state", where);
  const std::string wi = where + "/initial_state";
  const auto& pose = require_object(require_object(s.initial_state, "uav", wi), "pose", wi + "/uav");
  s.mission.home_W_m = {require_number(pose, "x", wi + "/uav/pose"), require_number(pose, "y", wi + "/uav/pose"), 0.0};
  airspace_from_initial_state(s.initial_state, wi, s.airspace);

  const auto& m = require_object(j, "mission", where);
  const std::string wm = where + "/mission";
  s.mission.name = s.name;
  s.mission.description = require_string(m, "description", wm);
  s.mission.cruise_altitude_m = number_or(m, "cruise_altitude_m", 60.0, wm);
  s.mission.cruise_speed_mps = number_or(m, "cruise_speed_mps", 8.0, wm);
  s.mission.time_limit_s = number_or(m, "time_limit_s", 900.0, wm);
  if (!s.airspace.altitude_ok(s.mission.cruise_altitude_m)) {
    throw InputError(wm + "/cruise_altitude_m: outside the airspace's alt_bounds");
  }
  const auto& objectives = require_array(m, "objectives", wm);
  for (std::size_t i = 0; i < objectives.size(); ++i) {
    s.mission.objectives.push_back(objective(objectives[i], wm + "/objectives/" + std::to_string(i)));
  }
  if (s.mission.objectives.empty()) throw InputError(wm + "/objectives: a mission needs at least one objective");

  if (j.contains("airspace")) {
    const auto& a = require_object(j, "airspace", where);
    const std::string wa = where + "/airspace";
    if (a.contains("no_fly_zones")) {
      const auto& zones = require_array(a, "no_fly_zones", wa);
      for (std::size_t i = 0; i < zones.size(); ++i) {
        s.airspace.no_fly_zones.push_back(no_fly_zone(zones[i], wa + "/no_fly_zones/" + std::to_string(i)));
      }
    }
    if (a.contains("traffic")) {
      const auto& peers = require_array(a, "traffic", wa);
      for (std::size_t i = 0; i < peers.size(); ++i) {
        s.airspace.traffic.push_back(traffic(peers[i], wa + "/traffic/" + std::to_string(i)));
      }
    }
  }
  if (j.contains("network")) {
    const auto& n = require_object(j, "network", where);
    const std::string wn = where + "/network";
    s.network.initial_slice = n.value("initial_slice", s.network.initial_slice);
    if (s.network.initial_slice != "URLLC" && s.network.initial_slice != "eMBB" && s.network.initial_slice != "mMTC") {
      throw InputError(wn + "/initial_slice: '" + s.network.initial_slice + "' is not URLLC, eMBB or mMTC");
    }
    if (n.contains("degradations")) {
      const auto& d = require_array(n, "degradations", wn);
      for (std::size_t i = 0; i < d.size(); ++i) {
        const std::string wd = wn + "/degradations/" + std::to_string(i);
        NetworkScript::Window w{require_number(d[i], "start_s", wd), require_number(d[i], "duration_s", wd)};
        if (w.start_s < 0.0 || !(w.duration_s > 0.0)) throw InputError(wd + ": start_s >= 0 and duration_s > 0");
        s.network.degradations.push_back(w);
      }
    }
    if (n.contains("trace")) {
      std::string t = require_string(n, "trace", wn);
      if (t.rfind("alphabench:", 0) != 0 && std::filesystem::path(t).is_relative()) t = (base_dir / t).string();
      s.network.trace = t;
      s.network.trace_period_s = number_or(n, "trace_period_s", s.network.trace_period_s, wn);
    }
    if (n.contains("link")) s.network.link_overrides = require_object(n, "link", wn);
  }
  // Every point of the mission must be inside the geofence.
  for (std::size_t i = 0; i < s.mission.objectives.size(); ++i) {
    const auto& o = s.mission.objectives[i];
    std::vector<Eigen::Vector2d> pts = o.area;
    if (o.type == agent::ObjectiveType::kImagePoint || o.type == agent::ObjectiveType::kDelivery) pts.push_back(o.point);
    for (const auto& p : pts) {
      if (!s.airspace.inside_geofence(p)) {
        throw InputError(wm + "/objectives/" + std::to_string(i) + ": a point lies outside the geofence");
      }
    }
  }
  return s;
}

std::vector<std::string> builtin_scenario_names() {
  std::vector<std::string> names;
  for (const auto& [name, text] : builtin_scenarios()) names.emplace_back(name);
  return names;
}

Scenario load_scenario(const std::string& spec, const std::filesystem::path& shared_dir) {
  for (const auto& [name, text] : builtin_scenarios()) {
    if (name == spec) return scenario_from_json(common::parse_json_text(text, "scenario " + std::string(name)), "scenario " + std::string(name), ".");
  }
  if (spec.rfind("alphabench:", 0) == 0) {
    std::filesystem::path p = spec.substr(11);
    if (p.is_relative()) p = shared_dir / "alphabench" / "eval_runs" / p;
    const auto doc = common::load_json_file(p);
    const auto& state = doc.contains("initial_state") ? require_object(doc, "initial_state", p.string()) : doc;
    Scenario s = scenario_from_initial_state(state, p.string() + "/initial_state");
    s.source = spec;
    return s;
  }
  std::error_code ec;
  if (!std::filesystem::exists(spec, ec)) {
    std::string names;
    for (const auto& n : builtin_scenario_names()) names += (names.empty() ? "" : ", ") + n;
    throw InputError("scenario '" + spec + "' is not a built-in scenario (" + names +
                     "), an existing file, or alphabench:<path>");
  }
  return scenario_from_json(common::load_json_file(spec), spec, std::filesystem::path(spec).parent_path());
}

Scenario scenario_from_initial_state(const nlohmann::json& state, const std::string& where) {
  Scenario s;
  s.source = where;
  s.initial_state = state;
  airspace_from_initial_state(state, where, s.airspace);
  const auto& pose = require_object(require_object(state, "uav", where), "pose", where + "/uav");
  const Eigen::Vector2d home(require_number(pose, "x", where + "/uav/pose"), require_number(pose, "y", where + "/uav/pose"));
  s.mission.home_W_m = {home.x(), home.y(), 0.0};
  const double z = require_number(pose, "z", where + "/uav/pose");
  s.name = "alphabench";
  s.description = "a default mission for an α³-Bench initial state";
  s.mission.name = s.name;
  // Fly at the corpus altitude where the envelope allows, never above 120 m.
  s.mission.cruise_altitude_m = std::clamp(std::min(z, 120.0), s.airspace.min_altitude_m + 5.0,
                                           std::max(s.airspace.min_altitude_m + 5.0, s.airspace.max_altitude_m - 5.0));
  // Payloads beyond an Iris' lift need the heavy-lift airframe.
  double payload_kg = 0.0;
  if (state["uav"].contains("payloads") && state["uav"]["payloads"].is_array()) {
    for (const auto& p : state["uav"]["payloads"]) payload_kg += p.value("mass_kg", 0.0);
  }
  s.airframe = payload_kg > 0.5 ? "heavy-lift" : "iris";
  // The image point: 250 m from home toward the geofence's centre (or east without one).
  Eigen::Vector2d centre = home + Eigen::Vector2d(250.0, 0.0);
  if (s.airspace.geofence.size() >= 3) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const auto& p : s.airspace.geofence) c += p;
    c /= static_cast<double>(s.airspace.geofence.size());
    const Eigen::Vector2d dir = (c - home).norm() > 1.0 ? Eigen::Vector2d((c - home).normalized()) : Eigen::Vector2d(1, 0);
    centre = home + 250.0 * dir;
  }
  agent::Objective image;
  image.id = "point-of-interest";
  image.type = agent::ObjectiveType::kImagePoint;
  image.point = centre;
  image.radius_m = 20.0;
  image.altitude_m = s.mission.cruise_altitude_m;
  image.description = "image the point of interest";
  agent::Objective back;
  back.id = "home";
  back.type = agent::ObjectiveType::kReturnAndLand;
  back.radius_m = 5.0;
  s.mission.objectives = {image, back};
  char text[200];
  std::snprintf(text, sizeof text, "Image the point of interest at (%.0f, %.0f) from %.0f m, then return and land.",
                centre.x(), centre.y(), s.mission.cruise_altitude_m);
  s.mission.description = text;
  s.network.initial_slice = "eMBB";
  return s;
}

}  // namespace a3::rigs
