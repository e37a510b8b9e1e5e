// Scenario files: schema, typed parse, semantic rules.
#include "rigs/scenario/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "bridge/fc/fc_params.hpp"
#include "common/json_file.hpp"
#include "common/json_text.hpp"
#include "rigs/scenario/builtin_scenarios.hpp"
#include "rigs/scenario/scenario_airspace.hpp"
#include "rigs/scenario/scenario_checks.hpp"
#include "rigs/scenario/scenario_schema.hpp"

namespace a3::rigs {
namespace {

using common::InputError;
using common::number_or;
using common::require_array;
using common::require_object;
using common::require_string;

agent::ObjectiveType objective_type(const std::string& s, const std::string& where) {
  if (s == "survey") return agent::ObjectiveType::kSurvey;
  if (s == "image_point") return agent::ObjectiveType::kImagePoint;
  if (s == "delivery") return agent::ObjectiveType::kDelivery;
  if (s == "thermal_search") return agent::ObjectiveType::kThermalSearch;
  if (s == "return_and_land") return agent::ObjectiveType::kReturnAndLand;
  throw InputError(where + ": unknown objective type '" + s +
                   "' (survey, image_point, delivery, thermal_search, return_and_land)");
}

const nlohmann::json& field_or_null(const nlohmann::json& j, const char* key) {
  static const nlohmann::json kNull;
  return j.contains(key) ? j[key] : kNull;
}

void objective_place(const nlohmann::json& j, const std::string& w, agent::Objective& o) {
  switch (o.type) {
    case agent::ObjectiveType::kSurvey:
      o.area = parse_polygon(require_array(j, "area", w), w + "/area");
      o.images_required = static_cast<int>(number_or(j, "images_required", o.images_required, w));
      if (o.images_required < 1) throw InputError(w + "/images_required: must be >= 1");
      break;
    case agent::ObjectiveType::kThermalSearch:
      o.area = parse_polygon(require_array(j, "area", w), w + "/area");
      o.hidden_target = parse_point2(field_or_null(j, "target"), w + "/target");
      if (!common::polygon_contains(o.area, o.hidden_target)) throw InputError(w + "/target: must lie inside the area");
      break;
    case agent::ObjectiveType::kImagePoint:
      o.point = parse_point2(field_or_null(j, "point"), w + "/point");
      break;
    case agent::ObjectiveType::kDelivery:
      o.point = parse_point2(field_or_null(j, "point"), w + "/point");
      o.drop_altitude_m = number_or(j, "drop_altitude_m", o.drop_altitude_m, w);
      break;
    case agent::ObjectiveType::kReturnAndLand:
      o.radius_m = number_or(j, "radius_m", 5.0, w);
      break;
  }
}

agent::Objective objective(const nlohmann::json& j, const std::string& w) {
  agent::Objective o;
  o.id = require_string(j, "id", w);
  o.type = objective_type(require_string(j, "type", w), w + "/type");
  o.description = j.contains("description") ? require_string(j, "description", w) : "";
  o.radius_m = number_or(j, "radius_m", o.radius_m, w);
  o.altitude_m = number_or(j, "altitude_m", o.altitude_m, w);
  const std::string default_sensor = o.type == agent::ObjectiveType::kThermalSearch ? "thermal" : "rgb";
  o.sensor = j.contains("sensor") ? require_string(j, "sensor", w) : default_sensor;
  objective_place(j, w, o);
  if (!(o.radius_m > 0.0)) throw InputError(w + "/radius_m: must be > 0");
  if (!(o.altitude_m > 0.0)) throw InputError(w + "/altitude_m: must be > 0");
  return o;
}

agent::Mission mission(const nlohmann::json& m, const std::string& wm) {
  agent::Mission out;
  out.description = require_string(m, "description", wm);
  out.cruise_altitude_m = number_or(m, "cruise_altitude_m", 60.0, wm);
  out.cruise_speed_mps = number_or(m, "cruise_speed_mps", 8.0, wm);
  out.time_limit_s = number_or(m, "time_limit_s", 900.0, wm);
  const auto& objectives = require_array(m, "objectives", wm);
  for (std::size_t i = 0; i < objectives.size(); ++i) {
    out.objectives.push_back(objective(objectives[i], wm + "/objectives/" + std::to_string(i)));
  }
  if (out.objectives.empty()) throw InputError(wm + "/objectives: a mission needs at least one objective");
  return out;
}

// The scenario's airframe with its payloads. Throws naming /airframe.
dynamics::VehicleParams loaded_airframe(const Scenario& s, const std::string& where) {
  try {
    return dynamics::with_payloads(dynamics::airframe_by_name_or_path(s.airframe), s.start.payloads);
  } catch (const std::exception& e) {
    throw InputError(where + ": /airframe: " + e.what());
  }
}

void check_semantics(const Scenario& s, const std::string& where) {
  throw_if_problems(scenario_problems(s, loaded_airframe(s, where), bridge::FcParams{}.limits.max_tilt_deg, where));
}

Scenario parse_scenario(const nlohmann::json& j, const std::string& where, const std::filesystem::path& base_dir) {
  const std::string root = where + ": ";
  Scenario s;
  s.source = where;
  s.name = require_string(j, "name", root);
  s.description = j.contains("description") ? require_string(j, "description", root) : "";
  s.airframe = j.contains("airframe") ? require_string(j, "airframe", root) : s.airframe;
  s.initial_state = require_object(j, "initial_state", root);
  s.start = parse_initial_state(s.initial_state, root + "/initial_state");
  s.airspace = parse_airspace(s.start, field_or_null(j, "airspace"), root + "/airspace");
  s.mission = mission(require_object(j, "mission", root), root + "/mission");
  s.mission.name = s.name;
  s.mission.home_W_m = {s.start.pose_W_m.x(), s.start.pose_W_m.y(), 0.0};
  if (j.contains("network")) {
    s.network = linkemu::parse_scenario_network(require_object(j, "network", root), root + "/network", base_dir);
  }
  return s;
}

std::filesystem::path alphabench_path(const std::string& spec, const std::filesystem::path& shared_dir) {
  std::filesystem::path p = spec.substr(11);
  if (p.is_relative()) p = shared_dir / "alphabench" / "eval_runs" / p;
  return p;
}

// Where the default mission images: 250 m from home toward the geofence's centre (or east
// without one), nearer home when that point lies outside the geofence.
Eigen::Vector2d default_image_point(const agent::Airspace& airspace, const Eigen::Vector2d& home) {
  if (airspace.geofence.size() < 3) return home + Eigen::Vector2d(250.0, 0.0);
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : airspace.geofence) c += p;
  c /= static_cast<double>(airspace.geofence.size());
  const Eigen::Vector2d dir = (c - home).norm() > 1.0 ? Eigen::Vector2d((c - home).normalized()) : Eigen::Vector2d(1, 0);
  double distance_m = 250.0;
  while (distance_m > 20.0 && !airspace.inside_geofence(home + distance_m * dir)) distance_m *= 0.5;
  return home + distance_m * dir;
}

agent::Mission default_mission(const Scenario& s) {
  agent::Mission m;
  m.name = s.name;
  m.home_W_m = {s.start.pose_W_m.x(), s.start.pose_W_m.y(), 0.0};
  // Fly at the corpus altitude where the envelope allows, never above 120 m.
  m.cruise_altitude_m = std::clamp(std::min(s.start.pose_W_m.z(), 120.0), s.airspace.min_altitude_m + 5.0,
                                   std::max(s.airspace.min_altitude_m + 5.0, s.airspace.max_altitude_m - 5.0));
  agent::Objective image;
  image.id = "point-of-interest";
  image.type = agent::ObjectiveType::kImagePoint;
  image.point = default_image_point(s.airspace, m.home_W_m.head<2>());
  image.radius_m = 20.0;
  image.altitude_m = m.cruise_altitude_m;
  image.description = "image the point of interest";
  agent::Objective back;
  back.id = "home";
  back.type = agent::ObjectiveType::kReturnAndLand;
  back.radius_m = 5.0;
  m.objectives = {image, back};
  char text[200];
  std::snprintf(text, sizeof text, "Image the point of interest at (%.0f, %.0f) from %.0f m, then return and land.",
                image.point.x(), image.point.y(), m.cruise_altitude_m);
  m.description = text;
  return m;
}

}  // namespace

nlohmann::json Scenario::airspace_brief() const { return rigs::airspace_brief(airspace); }

Scenario scenario_from_json(const nlohmann::json& j, const std::string& where, const std::filesystem::path& base_dir) {
  throw_if_problems(scenario_schema_problems(j, where));
  Scenario s = parse_scenario(j, where, base_dir);
  check_semantics(s, where);
  return s;
}

std::vector<std::string> builtin_scenario_names() {
  std::vector<std::string> names;
  for (const auto& [name, text] : builtin_scenarios()) names.emplace_back(name);
  return names;
}

std::optional<nlohmann::json> builtin_scenario_json(const std::string& name) {
  for (const auto& [builtin, text] : builtin_scenarios()) {
    if (builtin == name) return common::parse_json_text(text, "scenario " + name);
  }
  return std::nullopt;
}

Scenario load_scenario(const std::string& spec, const std::filesystem::path& shared_dir) {
  if (const auto builtin = builtin_scenario_json(spec)) return scenario_from_json(*builtin, "scenario " + spec, ".");
  if (spec.rfind("alphabench:", 0) == 0) {
    const std::filesystem::path p = alphabench_path(spec, shared_dir);
    const auto doc = common::load_json_file(p);
    Scenario s = scenario_from_initial_state(initial_state_of(doc, p.string()), p.string());
    s.source = spec;
    return s;
  }
  if (spec.rfind("gen:", 0) == 0) {
    throw InputError("scenario '" + spec + "': a generated mission is made before loading "
                     "(rigs/generator/scenario_spec.hpp's load_scenario_spec), not by the loader");
  }
  std::error_code ec;
  if (!std::filesystem::exists(spec, ec)) {
    std::string names;
    for (const auto& n : builtin_scenario_names()) names += (names.empty() ? "" : ", ") + n;
    throw InputError("scenario '" + spec + "' is not a built-in scenario (" + names +
                     "), a generated mission (gen:SEED[:easy|medium|hard|knob=value+...], e.g. gen:7:hard), an existing file, or "
                     "alphabench:<path>");
  }
  return scenario_from_json(common::load_json_file(spec), spec, std::filesystem::path(spec).parent_path());
}

Scenario scenario_from_initial_state(const nlohmann::json& state, const std::string& where) {
  throw_if_problems(corpus_initial_state_problems(state, where));
  Scenario s;
  s.source = where;
  s.name = "alphabench";
  s.description = "a default mission for an α³-Bench initial state";
  s.initial_state = state;
  s.start = parse_initial_state(state, where + ": /initial_state");
  s.airspace = parse_airspace(s.start, nullptr, where);
  // Payloads beyond an Iris' lift need the heavy-lift airframe.
  double payload_kg = 0.0;
  for (const auto& p : s.start.payloads) payload_kg += p.mass_kg;
  s.airframe = payload_kg > 0.5 ? "heavy-lift" : "iris";
  s.mission = default_mission(s);
  s.network.initial_slice = "eMBB";
  check_semantics(s, where);
  return s;
}

}  // namespace a3::rigs
