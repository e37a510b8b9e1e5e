// Motion tools that plan an onboard route on the vehicle: execute_maneuver (orbit, survey
// with optional captures, yaw) and return_to_home (direct, or a detour around no-fly zones
// then a landing). Each answers once the fc's status for its first command arrives. ETAs are
// at the ground speed made good in the estimated wind, and name that wind.
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "vehicle/maneuvers.hpp"
#include "vehicle/motion_steps.hpp"
#include "vehicle/observation_json.hpp"
#include "vehicle/path_planner.hpp"
#include "vehicle/vehicle_tools.hpp"

namespace a3::vehicle {
namespace {

// A maneuver's waypoints and the observation's fields about it, or the error that answered.
struct ManeuverPlan {
  std::vector<RoutePoint> points;
  nlohmann::json extra;
  std::string capture_sensor = "rgb";
};

std::optional<ManeuverPlan> failed(VehicleServices& vehicle, const std::string& error) {
  vehicle.finish_error(error);
  return std::nullopt;
}

std::optional<ManeuverPlan> plan_orbit(VehicleServices& vehicle, const nlohmann::json& args,
                                       const Eigen::Vector3d& p, double z) {
  if (!args.contains("center")) return failed(vehicle, "args/center: required for maneuver orbit");
  if (!args.contains("radius_m")) return failed(vehicle, "args/radius_m: required for maneuver orbit");
  ManeuverPlan plan;
  const Eigen::Vector2d centre(args["center"][0].get<double>(), args["center"][1].get<double>());
  const double radius = args["radius_m"].get<double>();
  for (const auto& w : orbit_waypoints(centre, radius, z, p.head<2>(), vehicle.config().route.orbit_max_chord_m)) {
    plan.points.push_back(RoutePoint{w});
  }
  plan.extra["radius_m"] = rounded(radius, 1);
  return plan;
}

// "" when the sensor can capture on a survey, else the error.
std::string survey_sensor_problem(VehicleServices& vehicle, const std::string& name) {
  const SensorInfo* s = vehicle.sensor_suite().find(name);
  if (s == nullptr) return "args/sensor: unknown sensor '" + name + "'";
  if (!s->imaging) return "args/sensor: " + name + " does not take images";
  if (!s->usable) return "args/sensor: " + name + " is " + s->health;
  if (!vehicle.sensor_suite().active(name)) return "args/sensor: " + name + " is not active (activate_sensor first)";
  return "";
}

std::optional<ManeuverPlan> plan_survey(VehicleServices& vehicle, const nlohmann::json& args,
                                        const Eigen::Vector3d& p, double z) {
  if (!args.contains("area")) return failed(vehicle, "args/area: required for maneuver survey");
  const RouteConfig& route = vehicle.config().route;
  ManeuverPlan plan;
  common::Polygon2d area;
  for (const auto& v : args["area"]) area.emplace_back(v[0].get<double>(), v[1].get<double>());
  const double spacing = args.contains("spacing_m") ? args["spacing_m"].get<double>() : route.default_survey_spacing_m;
  const bool capture_on = args.value("capture", false);
  if (capture_on) {
    plan.capture_sensor = args.value("sensor", std::string("rgb"));
    if (auto problem = survey_sensor_problem(vehicle, plan.capture_sensor); !problem.empty()) {
      return failed(vehicle, problem);
    }
  }
  SurveyPattern pattern;
  try {
    pattern = survey_waypoints(area, spacing, z, p.head<2>(), route.max_waypoints);
  } catch (const std::invalid_argument& e) {
    return failed(vehicle, std::string("args/") + e.what());
  }
  for (const auto& w : pattern.waypoints) plan.points.push_back(RoutePoint{w, capture_on});
  plan.extra["lines"] = pattern.lines;
  plan.extra["spacing_m"] = rounded(spacing, 1);
  plan.extra["captures"] = capture_on ? pattern.waypoints.size() : 0;
  if (capture_on) plan.extra["sensor"] = plan.capture_sensor;
  return plan;
}

std::optional<ManeuverPlan> plan_yaw(VehicleServices& vehicle, const nlohmann::json& args, const Eigen::Vector3d& p) {
  if (!args.contains("heading_deg")) return failed(vehicle, "args/heading_deg: required for maneuver yaw");
  const double heading = args["heading_deg"].get<double>();
  if (!std::isfinite(heading)) return failed(vehicle, "args/heading_deg: must be finite");
  ManeuverPlan plan;
  plan.points.push_back(RoutePoint{p, false, heading});
  plan.extra["heading_deg"] = rounded(heading, 1);
  return plan;
}

void execute_maneuver(VehicleServices& vehicle, const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(vehicle, &p, &battery)) return;
  const std::string maneuver = args.at("maneuver").get<std::string>();
  const double z = args.contains("z") ? args["z"].get<double>() : p.z();
  std::optional<ManeuverPlan> plan = maneuver == "orbit"    ? plan_orbit(vehicle, args, p, z)
                                     : maneuver == "survey" ? plan_survey(vehicle, args, p, z)
                                                            : plan_yaw(vehicle, args, p);
  if (!plan) return;  // answered with the error
  const std::size_t max_waypoints = vehicle.config().route.max_waypoints;
  if (plan->points.size() > max_waypoints) {
    return vehicle.finish_error("args: the " + maneuver + " needs " + std::to_string(plan->points.size()) +
                                " waypoints, more than the " + std::to_string(max_waypoints) + " a route may have");
  }
  const double speed = vehicle.speed_mps();
  const auto targets = positions(plan->points);
  if (auto why = vehicle.gate().check_route(p, targets, speed, battery); !why.empty()) {
    return vehicle.finish_gate_refusal(why);
  }
  nlohmann::json extra = {{"maneuver", maneuver}};
  for (auto& [key, value] : plan->extra.items()) extra[key] = value;
  extra["waypoints"] = targets.size();
  extra["route_length_m"] = rounded(route_length_m(p, targets), 1);
  extra["eta_s"] = rounded(vehicle.gate().energy().route_time_s(p, targets, speed), 1);
  extra["wind"] = wind_estimate_json(vehicle.wind_estimate());
  start_route(vehicle, OnboardRoute(maneuver, std::move(plan->points), speed, RouteEnd::kHold, plan->capture_sensor),
              std::move(extra));
}

// The straight return crosses a no-fly zone: fly a detour at the return altitude, then land.
void return_by_detour(VehicleServices& vehicle, const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& legs,
                      double speed, const std::string& blocked) {
  const SafetyGate& gate = vehicle.gate();
  const Eigen::Vector3d& home = vehicle.config().home_W_m;
  std::string why;
  const auto plan = plan_path(gate, p, home.head<2>(), legs.front().z(), vehicle.config().planner, &why);
  if (!plan) return vehicle.finish_gate_refusal(blocked + "; no detour: " + why);
  const Eigen::Vector3d above_home = plan->waypoints.back();
  if (auto problem = gate.check_descent(above_home); !problem.empty()) return vehicle.finish_gate_refusal(problem);
  std::vector<RoutePoint> points;
  for (const auto& w : plan->waypoints) points.push_back(RoutePoint{w});
  nlohmann::json extra = {{"route", "detour"},
                          {"home", point_json(home)},
                          {"avoids", plan->avoided},
                          {"waypoints", points.size()},
                          {"route_length_m", rounded(plan->length_m, 1)},
                          {"eta_s", rounded(gate.energy().route_time_s(p, plan->waypoints, speed) +
                                                above_home.z() / gate.energy().descent_speed_mps,
                                            1)},
                          {"wind", wind_estimate_json(vehicle.wind_estimate())}};
  start_route(vehicle, OnboardRoute("return_to_home", std::move(points), speed, RouteEnd::kLand), std::move(extra));
}

void return_to_home(VehicleServices& vehicle, const nlohmann::json&) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(vehicle, &p, &battery)) return;  // the return is never refused for the battery
  const ToolServerConfig& config = vehicle.config();
  const Eigen::Vector3d& home = config.home_W_m;
  const auto legs = return_home_legs(p, home, config.gate.return_altitude_m, config.airspace.min_altitude_m,
                                     config.airspace.max_altitude_m);
  const double speed = std::max(vehicle.speed_mps(), vehicle.gate().energy().cruise_speed_mps);
  std::string blocked;
  Eigen::Vector3d from = p;
  for (std::size_t i = 0; i < legs.size() && blocked.empty(); ++i) {
    blocked = vehicle.gate().check_leg(from, legs[i], i == 0 ? "the climb" : i == 1 ? "the flight home" : "the descent");
    from = legs[i];
  }
  if (!blocked.empty()) return return_by_detour(vehicle, p, legs, speed, blocked);
  vehicle.cancel_route("return_to_home");
  const int32_t seq = vehicle.send_fc(a3lcm::fc_command_t::RETURN_HOME, home, 0.0, kNoYaw);
  nlohmann::json extra = {{"route", "direct"},
                          {"home", point_json(home)},
                          {"distance_m", rounded((home.head<2>() - p.head<2>()).norm(), 1)},
                          {"eta_s", rounded(vehicle.gate().energy().route_time_s(p, legs, speed), 1)},
                          {"wind", wind_estimate_json(vehicle.wind_estimate())}};
  vehicle.await_status(seq, [&vehicle, extra](const a3lcm::fc_status_t* s) { answer_motion(vehicle, s, extra); });
}

}  // namespace

void add_route_tools(ToolHandlers& handlers) {
  handlers.add_tool("execute_maneuver", execute_maneuver);
  handlers.add_tool("return_to_home", return_to_home);
}

}  // namespace a3::vehicle
