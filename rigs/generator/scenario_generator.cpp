// Drawing a mission layout from a seed, writing it as a scenario document, and checking it.
#include "rigs/generator/scenario_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "common/json_file.hpp"
#include "common/polygon.hpp"
#include "common/rng.hpp"
#include "common/text_format.hpp"
#include "dynamics/quadrotor_model.hpp"
#include "dynamics/vehicle_params.hpp"
#include "rigs/generator/scenario_generator_check.hpp"
#include "rigs/generator/scenario_generator_layout.hpp"

namespace a3::rigs {
namespace {

using agent::ObjectiveType;

constexpr int kMaxDraws = 64;
constexpr double kHoverThrottleLimit = 0.8;  // the rig refuses above 0.85: keep a margin

nlohmann::json xy(const Eigen::Vector2d& p) { return nlohmann::json::array({p.x(), p.y()}); }

nlohmann::json polygon_json(const common::Polygon2d& poly) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : poly) out.push_back(xy(p));
  return out;
}

using common::formatted;

std::string area_words(const common::Polygon2d& a) {
  return formatted("the rectangle from (%.0f, %.0f) to (%.0f, %.0f)", a[0].x(), a[0].y(), a[2].x(), a[2].y());
}

nlohmann::json objective_json(const DrawnObjective& o, std::string* words) {
  nlohmann::json j = {{"id", o.id}, {"type", agent::to_string(o.type)}};
  switch (o.type) {
    case ObjectiveType::kSurvey:
      j.update({{"area", polygon_json(o.area)}, {"altitude_m", o.altitude_m}, {"images_required", o.images_required},
                {"sensor", "rgb"}, {"description", "lawnmower survey of " + o.id}});
      *words = "survey " + o.id + " (" + area_words(o.area) + ") with the RGB camera from " +
               formatted("%.0f m, at least %.0f images", o.altitude_m, static_cast<double>(o.images_required));
      break;
    case ObjectiveType::kThermalSearch:
      j.update({{"area", polygon_json(o.area)}, {"target", xy(o.target)}, {"radius_m", o.radius_m},
                {"altitude_m", o.altitude_m}, {"sensor", "thermal"}, {"description", "find the person with the thermal camera"}});
      *words = "search " + area_words(o.area) + " with the thermal camera from " + formatted("%.0f m", o.altitude_m) +
               " for a person on the ground";
      break;
    case ObjectiveType::kImagePoint:
      j.update({{"point", xy(o.point)}, {"radius_m", o.radius_m}, {"altitude_m", o.altitude_m}, {"sensor", o.sensor}});
      *words = "image " + o.id + formatted(" at (%.0f, %.0f) from %.0f m", o.point.x(), o.point.y(), o.altitude_m) +
               " with the " + (o.sensor == "rgb" ? std::string("RGB") : o.sensor) + " camera";
      break;
    case ObjectiveType::kDelivery:
      j.update({{"point", xy(o.point)}, {"radius_m", o.radius_m}, {"drop_altitude_m", o.drop_altitude_m},
                {"description", formatted("descend to %.0f m or lower over the drop point and hold 1 s", o.drop_altitude_m)}});
      *words = "deliver the parcel to " + o.id + formatted(" at (%.0f, %.0f): descend to %.0f m or lower over it", o.point.x(),
                                                     o.point.y(), o.drop_altitude_m);
      break;
    case ObjectiveType::kReturnAndLand:
      break;
  }
  return j;
}

nlohmann::json objectives_json(const Layout& l, std::string* mission_words) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& o : l.objectives) {
    std::string words;
    out.push_back(objective_json(o, &words));
    *mission_words += (mission_words->empty() ? "" : "; ") + words;
  }
  out.push_back({{"id", "home"}, {"type", "return_and_land"}, {"radius_m", 5}, {"description", "return to the launch point and land"}});
  return out;
}

std::string mission_words(const Layout& l, const std::string& objectives) {
  std::string out = objectives;
  out[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(out[0])));
  out += formatted(", cruising at %.0f m", l.cruise_altitude_m);
  if (!l.zones.empty()) out += "; stay out of the no-fly zones on the way";
  if (!l.traffic.empty()) {
    out += "; other drones patrol across the route at cruise altitude: keep separation, negotiating with "
           "uav_swarm_agent over A2A";
  }
  return out + ". Then return and land.";
}

nlohmann::json initial_state_json(const Layout& l) {
  const double top = l.max_altitude_m;
  return {{"domain", "uav"},
          {"time_s", 0.0},
          {"env", l.env},
          {"airspace", {{"alt_bounds", {0.0, top}}, {"geofence", {{{"type", "polygon"}, {"points", polygon_json(l.geofence)}}}}}},
          {"uav", {{"pose", {{"x", l.home.x()}, {"y", l.home.y()}, {"z", 0.0}, {"yaw", l.home_yaw_deg}}},
                   {"speed_mps", 0.0},
                   {"energy", {{"battery_pct", 100.0}}},
                   {"sensors", {{"rgb", "ok"}, {"thermal", "ok"}, {"lidar", "ok"}, {"gnss", "ok"}, {"imu", "ok"},
                                {"magnetometer", "ok"}, {"barometer", "ok"}}},
                   {"payloads", l.payloads}}},
          {"policy", {{"alt_bounds", {0.0, top}}}},
          {"safety_flags", {{"nfz_violation", false}, {"separation_breach", false}}}};
}

nlohmann::json document_json(const GeneratorSpec& spec, const Layout& l, double time_limit_s) {
  std::string words;
  nlohmann::json objectives = objectives_json(l, &words);
  nlohmann::json doc = {
      {"name", "gen-" + std::to_string(spec.seed) + "-" + spec.knobs.difficulty},
      {"description", "Generated mission " + generator_spec_text(spec) + formatted(" (sized for %.0f dialogue turns).", static_cast<double>(spec.knobs.turns))},
      {"airframe", l.airframe},
      {"initial_state", initial_state_json(l)},
      {"mission", {{"description", mission_words(l, words)},
                   {"cruise_altitude_m", l.cruise_altitude_m},
                   {"cruise_speed_mps", l.cruise_speed_mps},
                   {"time_limit_s", time_limit_s},
                   {"objectives", objectives}}},
      {"network", l.network}};
  if (!l.zones.empty() || !l.traffic.empty()) {
    doc["airspace"] = nlohmann::json::object();
    if (!l.zones.empty()) doc["airspace"]["no_fly_zones"] = l.zones;
    if (!l.traffic.empty()) doc["airspace"]["traffic"] = l.traffic;
  }
  return doc;
}

// The heavy-lift when the Iris would hover above the throttle limit with the payload.
std::string airframe_for(const MissionKnobs& k) {
  if (k.airframe != "auto") return k.airframe;
  dynamics::VehicleParams iris = dynamics::airframe_by_name_or_path("iris");
  iris = dynamics::with_payloads(iris, {{"payload", k.payload_kg, 0.0, 0.0}});
  return dynamics::QuadrotorModel(iris).hover_throttle() <= kHoverThrottleLimit ? "iris" : "heavy-lift";
}

// Mission time: the route at the ground speed into the wind, with half again for turns taken
// slowly, plus the supervisor's waits between turns; rounded up to a minute.
double time_limit_for(const MissionCheck& check, int turns) {
  const double seconds = 1.5 * check.route_time_s + 10.0 * turns + 120.0;
  return 60.0 * std::ceil(seconds / 60.0);
}

// Mission seconds at which the vehicle lifts off after the pre-flight turn.
constexpr double kLiftoff_s = 5.0;

// When `phase` begins, mission seconds, from the reference flight's estimate.
double phase_start_s(const std::string& phase, const MissionCheck& check) {
  if (phase == "transit") return kLiftoff_s + check.phases.transit_s;
  if (phase == "objective") return kLiftoff_s + check.phases.objective_s;
  if (phase == "home") return kLiftoff_s + check.phases.home_s;
  return kLiftoff_s - 1.0;  // takeoff: from the launch command on
}

// Moves the degradation windows into the mission phases degrade_at asks for: window i into the
// phase after window i-1's, each starting a few seconds before its phase begins.
void place_degradations(nlohmann::json& network, const GeneratorSpec& spec, const MissionCheck& check) {
  const MissionKnobs& k = spec.knobs;
  if (k.degrade_at == "any" || !network.contains("degradations")) return;
  const std::vector<std::string>& phases = degradation_phases();
  std::size_t first = std::find(phases.begin(), phases.end(), k.degrade_at) - phases.begin();
  if (first >= phases.size()) {
    common::Rng rng = common::RngStreams(spec.seed).stream("scenario_generator/phases");
    first = static_cast<std::size_t>(rng.uniform01() * static_cast<double>(phases.size()));
  }
  for (std::size_t i = 0; i < network["degradations"].size(); ++i) {
    const std::string& phase = phases[(first + i) % phases.size()];
    network["degradations"][i]["start_s"] = std::round(std::max(0.0, phase_start_s(phase, check) - 5.0));
    network["degradations"][i]["phase"] = phase;
  }
}

}  // namespace

nlohmann::json generate_scenario_json(const GeneratorSpec& spec) {
  check_knobs(spec.knobs);
  const std::string where = "scenario " + generator_spec_text(spec);
  const std::string airframe = airframe_for(spec.knobs);
  std::string last_problem = "no layout drawn";
  for (int attempt = 0; attempt < kMaxDraws; ++attempt) {
    std::optional<Layout> layout = draw_layout(spec, airframe, attempt, &last_problem);
    if (!layout) continue;
    nlohmann::json doc = document_json(spec, *layout, 3600.0);
    const MissionCheck check = check_generated_mission(scenario_from_json(doc, where, "."));
    if (!check.problem.empty()) {
      last_problem = check.problem;
      continue;
    }
    doc["mission"]["time_limit_s"] = time_limit_for(check, spec.knobs.turns);
    place_degradations(doc["network"], spec, check);
    (void)scenario_from_json(doc, where, ".");
    return doc;
  }
  throw common::InputError(where + ": no flyable mission in " + std::to_string(kMaxDraws) +
                           " draws; the last failed on: " + last_problem);
}

Scenario generate_scenario(const std::string& spec_text) {
  const GeneratorSpec spec = parse_generator_spec(spec_text);
  Scenario s = scenario_from_json(generate_scenario_json(spec), "scenario " + spec_text, ".");
  s.source = spec_text;
  return s;
}

}  // namespace a3::rigs
