// initial_state JSON → InitialState.
#include "rigs/scenario/initial_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "common/json_file.hpp"
#include "rigs/scenario/uav_payloads.hpp"

namespace a3::rigs {
namespace {

using common::InputError;

double finite_number(const nlohmann::json& object, const std::string& key, const std::string& where) {
  const double v = common::require_number(object, key, where);
  if (!std::isfinite(v)) throw InputError(where + "/" + key + ": must be a finite number");
  return v;
}

double finite_number_or(const nlohmann::json& object, const std::string& key, double fallback, const std::string& where) {
  return object.contains(key) ? finite_number(object, key, where) : fallback;
}

Eigen::Vector2d point2(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 2 || !j[0].is_number() || !j[1].is_number() ||
      !std::isfinite(j[0].get<double>()) || !std::isfinite(j[1].get<double>())) {
    throw InputError(where + ": expected [x, y] in metres");
  }
  return {j[0].get<double>(), j[1].get<double>()};
}

AltitudeBounds bounds(const nlohmann::json& object, const std::string& where) {
  const auto& b = common::require_array(object, "alt_bounds", where);
  const std::string w = where + "/alt_bounds";
  if (b.size() != 2 || !b[0].is_number() || !b[1].is_number()) throw InputError(w + ": expected [min, max] in metres");
  const AltitudeBounds out{b[0].get<double>(), b[1].get<double>()};
  if (!std::isfinite(out.min_m) || !std::isfinite(out.max_m) || !(out.min_m < out.max_m)) {
    throw InputError(w + ": expected finite [min, max] with min < max");
  }
  return out;
}

common::Polygon2d geofence(const nlohmann::json& airspace, const std::string& where) {
  common::Polygon2d polygon;
  if (!airspace.contains("geofence")) return polygon;
  const auto& fences = common::require_array(airspace, "geofence", where);
  if (fences.empty()) return polygon;
  const std::string w = where + "/geofence/0";
  if (!fences[0].is_object()) throw InputError(w + ": expected an object {\"type\": \"polygon\", \"points\": [...]}");
  const auto& points = common::require_array(fences[0], "points", w);
  for (std::size_t i = 0; i < points.size(); ++i) polygon.push_back(point2(points[i], w + "/points/" + std::to_string(i)));
  if (polygon.size() < 3) throw InputError(w + "/points: a polygon needs at least 3 points");
  return polygon;
}

void parse_airspace(const nlohmann::json& state, const std::string& where, InitialState& out) {
  const auto& a = common::require_object(state, "airspace", where);
  const std::string w = where + "/airspace";
  if (a.contains("alt_bounds")) out.alt_bounds = bounds(a, w);
  out.geofence = geofence(a, w);
  if (state.contains("policy")) {
    const auto& p = common::require_object(state, "policy", where);
    if (p.contains("alt_bounds")) out.policy_alt_bounds = bounds(p, where + "/policy");
  }
}

// The sensor tools know sensors and payloads by one name each: a payload's id (its own or
// payload<i>) may be neither a sensor's name nor an earlier payload's id.
void refuse_clashing_payload_ids(const vehicle::SensorSuiteConfig& sensors, const std::string& w) {
  std::set<std::string> seen;
  for (std::size_t i = 0; i < sensors.payloads.size(); ++i) {
    const std::string& id = sensors.payloads[i].id;
    const std::string wi = w + "/payloads/" + std::to_string(i) + "/id: '" + id + "' ";
    if (sensors.sensor_health.count(id) != 0) throw InputError(wi + "is also the name of a sensor in uav/sensors");
    if (!seen.insert(id).second) throw InputError(wi + "is also the id of an earlier payload");
  }
}

void parse_uav(const nlohmann::json& state, const std::string& where, InitialState& out) {
  const auto& uav = common::require_object(state, "uav", where);
  const std::string w = where + "/uav";
  const auto& pose = common::require_object(uav, "pose", w);
  const std::string wp = w + "/pose";
  out.pose_W_m = {finite_number(pose, "x", wp), finite_number(pose, "y", wp), finite_number(pose, "z", wp)};
  out.yaw_deg = finite_number_or(pose, "yaw", 0.0, wp);
  out.speed_mps = finite_number_or(uav, "speed_mps", 0.0, w);
  const auto& energy = common::require_object(uav, "energy", w);
  out.battery_pct = finite_number(energy, "battery_pct", w + "/energy");
  if (!(out.battery_pct > 0.0 && out.battery_pct <= 100.0)) {
    throw InputError(w + "/energy/battery_pct: must be in (0, 100]");
  }
  if (uav.contains("sensors")) out.sensors.sensor_health = vehicle::parse_sensor_health(uav["sensors"], w + "/sensors");
  if (uav.contains("payloads")) {
    UavPayloads payloads = parse_uav_payloads(common::require_array(uav, "payloads", w), w + "/payloads");
    out.payloads = std::move(payloads.physical);
    out.sensors.payloads = std::move(payloads.declared);
  }
  refuse_clashing_payload_ids(out.sensors, w);
}

}  // namespace

InitialState parse_initial_state(const nlohmann::json& state, const std::string& where) {
  if (!state.is_object()) throw InputError(where + ": an initial_state must be a JSON object");
  InitialState out;
  out.domain = state.contains("domain") ? common::require_string(state, "domain", where) : out.domain;
  out.time_s = finite_number_or(state, "time_s", 0.0, where);
  out.env = vehicle::parse_weather_env(common::require_object(state, "env", where), where + "/env");
  parse_airspace(state, where, out);
  parse_uav(state, where, out);
  const AltitudeBounds e = out.envelope();
  if (!(e.min_m < e.max_m)) throw InputError(where + "/policy/alt_bounds: does not overlap airspace/alt_bounds");
  return out;
}

const nlohmann::json& initial_state_of(const nlohmann::json& document, const std::string& where) {
  if (document.is_object() && document.contains("initial_state")) {
    return common::require_object(document, "initial_state", where);
  }
  if (!document.is_object()) throw InputError(where + ": expected a JSON object");
  return document;
}

InitialState load_initial_state_file(const std::string& path) {
  const nlohmann::json doc = common::load_json_file(path);
  const bool episode = doc.is_object() && doc.contains("initial_state");
  return parse_initial_state(initial_state_of(doc, path), path + (episode ? ": /initial_state" : ": "));
}

dynamics::FlightStart flight_start(const InitialState& state) {
  dynamics::FlightStart f;
  f.p_W_m = state.pose_W_m;
  f.yaw_deg = state.yaw_deg;
  f.wind_mps = state.env.wind_mps;
  f.wind_dir_deg = state.env.wind_dir_deg;
  f.payloads = state.payloads;
  f.battery_pct = state.battery_pct;
  return f;
}

}  // namespace a3::rigs
