// Scenario airspace → agent::Airspace.
#include "rigs/scenario/scenario_airspace.hpp"

#include <cmath>

#include "common/json_file.hpp"

namespace a3::rigs {
namespace {

using common::InputError;

bool finite_number(const nlohmann::json& j) { return j.is_number() && std::isfinite(j.get<double>()); }

double finite_or(const nlohmann::json& j, const std::string& key, double fallback, const std::string& where) {
  if (!j.contains(key)) return fallback;
  if (!finite_number(j[key])) throw InputError(where + "/" + key + ": expected a finite number");
  return j[key].get<double>();
}

}  // namespace

Eigen::Vector2d parse_point2(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 2 || !finite_number(j[0]) || !finite_number(j[1])) {
    throw InputError(where + ": expected [x, y] in metres");
  }
  return {j[0].get<double>(), j[1].get<double>()};
}

Eigen::Vector3d parse_point3(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3 || !finite_number(j[0]) || !finite_number(j[1]) || !finite_number(j[2])) {
    throw InputError(where + ": expected [x, y, z] in metres");
  }
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

common::Polygon2d parse_polygon(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() < 3) throw InputError(where + ": a polygon needs at least 3 [x, y] points");
  common::Polygon2d out;
  for (std::size_t i = 0; i < j.size(); ++i) out.push_back(parse_point2(j[i], where + "/" + std::to_string(i)));
  return out;
}

agent::NoFlyZone parse_no_fly_zone(const nlohmann::json& j, const std::string& w) {
  agent::NoFlyZone z;
  z.id = common::require_string(j, "id", w);
  const std::string type = common::require_string(j, "type", w);
  if (type == "cylinder") {
    z.centre = parse_point2(j.contains("center") ? j["center"] : nlohmann::json(), w + "/center");
    z.radius_m = common::require_number(j, "radius_m", w);
    if (!(z.radius_m > 0.0)) throw InputError(w + "/radius_m: must be > 0");
  } else if (type == "polygon") {
    z.polygon = parse_polygon(common::require_array(j, "points", w), w + "/points");
  } else {
    throw InputError(w + "/type: '" + type + "' is not cylinder or polygon");
  }
  z.floor_m = finite_or(j, "floor_m", 0.0, w);
  z.ceiling_m = finite_or(j, "ceiling_m", 1e9, w);
  if (!(z.floor_m < z.ceiling_m)) throw InputError(w + "/ceiling_m: must be above floor_m");
  return z;
}

agent::TrafficPlan parse_traffic(const nlohmann::json& j, const std::string& w) {
  agent::TrafficPlan t;
  t.id = common::require_string(j, "id", w);
  const auto& path = common::require_array(j, "path", w);
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::string wp = w + "/path/" + std::to_string(i);
    agent::TrafficWaypoint p;
    p.t_s = common::require_number(path[i], "t_s", wp);
    p.p_W_m = parse_point3(path[i].contains("p") ? path[i]["p"] : nlohmann::json(), wp + "/p");
    if (!t.path.empty() && !(p.t_s > t.path.back().t_s)) throw InputError(wp + "/t_s: times must increase");
    t.path.push_back(p);
  }
  if (t.path.empty()) throw InputError(w + "/path: needs at least one point");
  t.min_separation_m = finite_or(j, "min_separation_m", t.min_separation_m, w);
  if (!(t.min_separation_m > 0.0)) throw InputError(w + "/min_separation_m: must be > 0");
  if (j.contains("yields_when_asked")) {
    if (!j["yields_when_asked"].is_boolean()) throw InputError(w + "/yields_when_asked: expected true or false");
    t.yields_when_asked = j["yields_when_asked"].get<bool>();
  }
  t.yield_climb_m = finite_or(j, "yield_climb_m", t.yield_climb_m, w);
  t.conflict_deadline_s = finite_or(j, "conflict_deadline_s", 0.0, w);
  return t;
}

agent::Airspace parse_airspace(const InitialState& state, const nlohmann::json& extras, const std::string& where) {
  agent::Airspace a;
  a.geofence = state.geofence;
  const AltitudeBounds envelope = state.envelope();
  if (std::isfinite(envelope.min_m)) a.min_altitude_m = envelope.min_m;
  if (std::isfinite(envelope.max_m)) a.max_altitude_m = envelope.max_m;
  if (extras.is_null()) return a;
  if (!extras.is_object()) throw InputError(where + ": expected an object");
  if (extras.contains("no_fly_zones")) {
    const auto& zones = common::require_array(extras, "no_fly_zones", where);
    for (std::size_t i = 0; i < zones.size(); ++i) {
      a.no_fly_zones.push_back(parse_no_fly_zone(zones[i], where + "/no_fly_zones/" + std::to_string(i)));
    }
  }
  if (extras.contains("traffic")) {
    const auto& peers = common::require_array(extras, "traffic", where);
    for (std::size_t i = 0; i < peers.size(); ++i) {
      a.traffic.push_back(parse_traffic(peers[i], where + "/traffic/" + std::to_string(i)));
    }
  }
  return a;
}

nlohmann::json airspace_brief(const agent::Airspace& airspace) {
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

}  // namespace a3::rigs
