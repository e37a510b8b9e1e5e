// Motion tools: gate checks, then fc commands (single commands or onboard routes). Each
// answers once the fc's status for its command arrives (or the wait times out).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "agent/vehicle/maneuvers.hpp"
#include "agent/vehicle/observation_json.hpp"
#include "agent/vehicle/tool_server_node.hpp"

namespace a3::agent {
namespace {

constexpr double kNoYaw = std::numeric_limits<double>::quiet_NaN();

Eigen::Vector3d point3(const nlohmann::json& a) {
  return Eigen::Vector3d(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
}

double route_length_m(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& points) {
  double length = 0.0;
  Eigen::Vector3d from = start;
  for (const auto& p : points) {
    length += (p - from).norm();
    from = p;
  }
  return length;
}

std::vector<Eigen::Vector3d> positions(const std::vector<RoutePoint>& points) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : points) out.push_back(p.p_W_m);
  return out;
}

}  // namespace

void ToolServerNode::start_route(OnboardRoute route, nlohmann::json extra) {
  cancel_route("superseded by " + route.name());
  route_.emplace(std::move(route));
  ++counters_->routes_started;
  const RoutePoint& first = route_->current();
  const int32_t seq = send_fc(a3lcm::fc_command_t::GOTO, first.p_W_m, route_->speed_mps(), first.yaw_deg);
  route_->leg_sent(seq);
  const double speed = route_->speed_mps();
  await_status(seq, [this, extra = std::move(extra), speed](const a3lcm::fc_status_t* s) {
    if (s != nullptr && s->last_command_accepted) speed_mps_ = speed;
    answer_motion(s, extra);
  });
}

bool ToolServerNode::require_telemetry(Eigen::Vector3d* p_W_m, double* battery_pct) {
  if (!fc_status_) {
    finish_gate_refusal("no telemetry from the flight controller yet: the vehicle's position is unknown");
    return false;
  }
  *p_W_m = *position();
  *battery_pct = fc_status_->battery_pct;
  return true;
}

void ToolServerNode::tool_takeoff(const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(&p, &battery)) return;
  const double altitude_m = args.at("altitude_m").get<double>();
  const Eigen::Vector3d target(p.x(), p.y(), altitude_m);
  std::string why = gate_.check_target(target, "take-off target");
  if (why.empty()) why = gate_.check_leg(p, target, "climb");
  if (why.empty()) why = gate_.check_battery(p, {target}, speed_mps_, battery);
  if (!why.empty()) return finish_gate_refusal(why);
  cancel_route("superseded by takeoff");
  const int32_t seq = send_fc(a3lcm::fc_command_t::TAKEOFF, target, 0.0, kNoYaw);
  const double eta_s = std::abs(altitude_m - p.z()) / gate_.energy().climb_speed_mps;
  await_status(seq, [this, target, altitude_m, eta_s](const a3lcm::fc_status_t* s) {
    if (s != nullptr && s->last_command_accepted) takeoff_target_W_m_ = target;
    answer_motion(s, {{"target_altitude_m", rounded(altitude_m, 1)}, {"eta_s", rounded(eta_s, 1)}});
  });
}

void ToolServerNode::tool_set_waypoint(const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(&p, &battery)) return;
  const Eigen::Vector3d target(args.at("x").get<double>(), args.at("y").get<double>(), args.at("z").get<double>());
  const double speed = args.contains("speed_mps") ? args["speed_mps"].get<double>() : speed_mps_;
  if (auto why = gate_.check_route(p, {target}, speed, battery); !why.empty()) return finish_gate_refusal(why);
  const double eta_s = gate_.energy().leg_time_s(p, target, speed);
  start_route(OnboardRoute("set_waypoint", {RoutePoint{target}}, speed, RouteEnd::kHold),
              {{"target", point_json(target)},
               {"distance_m", rounded((target - p).norm(), 1)},
               {"speed_mps", rounded(speed, 2)},
               {"eta_s", rounded(eta_s, 1)}});
}

void ToolServerNode::tool_set_altitude(const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(&p, &battery)) return;
  const Eigen::Vector3d target(p.x(), p.y(), args.at("z").get<double>());
  if (auto why = gate_.check_route(p, {target}, speed_mps_, battery); !why.empty()) return finish_gate_refusal(why);
  const double eta_s = gate_.energy().leg_time_s(p, target, speed_mps_);
  start_route(OnboardRoute("set_altitude", {RoutePoint{target}}, speed_mps_, RouteEnd::kHold),
              {{"target", point_json(target)}, {"eta_s", rounded(eta_s, 1)}});
}

void ToolServerNode::tool_navigate_to(const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(&p, &battery)) return;
  const auto& list = args.at("waypoints");
  if (list.size() > config_.route.max_waypoints) {
    return finish_error("args/waypoints: " + std::to_string(list.size()) + " waypoints, more than the " +
                        std::to_string(config_.route.max_waypoints) + " a route may have");
  }
  std::vector<RoutePoint> points;
  for (const auto& w : list) points.push_back(RoutePoint{point3(w)});
  const double speed = args.contains("speed_mps") ? args["speed_mps"].get<double>() : speed_mps_;
  const auto targets = positions(points);
  if (auto why = gate_.check_route(p, targets, speed, battery); !why.empty()) return finish_gate_refusal(why);
  const double eta_s = gate_.energy().route_time_s(p, targets, speed);
  const double length = route_length_m(p, targets);
  start_route(OnboardRoute("navigate_to", std::move(points), speed, RouteEnd::kHold),
              {{"waypoints", targets.size()},
               {"first_target", point_json(targets.front())},
               {"route_length_m", rounded(length, 1)},
               {"speed_mps", rounded(speed, 2)},
               {"eta_s", rounded(eta_s, 1)}});
}

void ToolServerNode::tool_execute_maneuver(const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(&p, &battery)) return;
  const std::string maneuver = args.at("maneuver").get<std::string>();
  const double z = args.contains("z") ? args["z"].get<double>() : p.z();
  std::vector<RoutePoint> points;
  nlohmann::json extra = {{"maneuver", maneuver}};
  std::string capture_sensor = "rgb";
  if (maneuver == "orbit") {
    if (!args.contains("center")) return finish_error("args/center: required for maneuver orbit");
    if (!args.contains("radius_m")) return finish_error("args/radius_m: required for maneuver orbit");
    const Eigen::Vector2d centre(args["center"][0].get<double>(), args["center"][1].get<double>());
    const double radius = args["radius_m"].get<double>();
    for (const auto& w : orbit_waypoints(centre, radius, z, p.head<2>(), config_.route.orbit_max_chord_m)) {
      points.push_back(RoutePoint{w});
    }
    extra["radius_m"] = rounded(radius, 1);
  } else if (maneuver == "survey") {
    if (!args.contains("area")) return finish_error("args/area: required for maneuver survey");
    common::Polygon2d area;
    for (const auto& v : args["area"]) area.emplace_back(v[0].get<double>(), v[1].get<double>());
    const double spacing = args.contains("spacing_m") ? args["spacing_m"].get<double>()
                                                      : config_.route.default_survey_spacing_m;
    const bool capture_on = args.value("capture", false);
    if (capture_on) {
      capture_sensor = args.value("sensor", std::string("rgb"));
      const SensorInfo* s = sensors_.find(capture_sensor);
      if (s == nullptr) return finish_error("args/sensor: unknown sensor '" + capture_sensor + "'");
      if (!s->imaging) return finish_error("args/sensor: " + capture_sensor + " does not take images");
      if (!s->usable) return finish_error("args/sensor: " + capture_sensor + " is " + s->health);
      if (!sensors_.active(capture_sensor)) {
        return finish_error("args/sensor: " + capture_sensor + " is not active (activate_sensor first)");
      }
    }
    SurveyPattern pattern;
    try {
      pattern = survey_waypoints(area, spacing, z, p.head<2>(), config_.route.max_waypoints);
    } catch (const std::invalid_argument& e) {
      return finish_error(std::string("args/") + e.what());
    }
    for (const auto& w : pattern.waypoints) points.push_back(RoutePoint{w, capture_on});
    extra["lines"] = pattern.lines;
    extra["spacing_m"] = rounded(spacing, 1);
    extra["captures"] = capture_on ? pattern.waypoints.size() : 0;
    if (capture_on) extra["sensor"] = capture_sensor;
  } else {  // yaw
    if (!args.contains("heading_deg")) return finish_error("args/heading_deg: required for maneuver yaw");
    const double heading = args["heading_deg"].get<double>();
    if (!std::isfinite(heading)) return finish_error("args/heading_deg: must be finite");
    points.push_back(RoutePoint{p, false, heading});
    extra["heading_deg"] = rounded(heading, 1);
  }
  if (points.size() > config_.route.max_waypoints) {
    return finish_error("args: the " + maneuver + " needs " + std::to_string(points.size()) +
                        " waypoints, more than the " + std::to_string(config_.route.max_waypoints) +
                        " a route may have");
  }
  const auto targets = positions(points);
  if (auto why = gate_.check_route(p, targets, speed_mps_, battery); !why.empty()) return finish_gate_refusal(why);
  extra["waypoints"] = targets.size();
  extra["route_length_m"] = rounded(route_length_m(p, targets), 1);
  extra["eta_s"] = rounded(gate_.energy().route_time_s(p, targets, speed_mps_), 1);
  start_route(OnboardRoute(maneuver, std::move(points), speed_mps_, RouteEnd::kHold, capture_sensor), std::move(extra));
}

void ToolServerNode::tool_hold() {
  cancel_route("hold");
  const Eigen::Vector3d p = position().value_or(Eigen::Vector3d::Zero());
  const int32_t seq = send_fc(a3lcm::fc_command_t::HOLD, p, 0.0, kNoYaw);
  await_status(seq, [this](const a3lcm::fc_status_t* s) { answer_motion(s, nlohmann::json::object()); });
}

void ToolServerNode::tool_land() {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(&p, &battery)) return;
  (void)battery;  // landing is never refused for the battery
  if (auto why = gate_.check_descent(p); !why.empty()) return finish_gate_refusal(why);
  cancel_route("land");
  const int32_t seq = send_fc(a3lcm::fc_command_t::LAND, p, 0.0, kNoYaw);
  const double eta_s = std::max(p.z(), 0.0) / gate_.energy().descent_speed_mps;
  await_status(seq, [this, eta_s](const a3lcm::fc_status_t* s) { answer_motion(s, {{"eta_s", rounded(eta_s, 1)}}); });
}

void ToolServerNode::tool_return_to_home() {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(&p, &battery)) return;
  (void)battery;  // the return is never refused for the battery
  const Eigen::Vector3d& home = config_.home_W_m;
  const auto legs = return_home_legs(p, home, config_.gate.return_altitude_m, config_.airspace.min_altitude_m,
                                     config_.airspace.max_altitude_m);
  const double speed = std::max(speed_mps_, gate_.energy().cruise_speed_mps);
  std::string blocked;
  Eigen::Vector3d from = p;
  for (std::size_t i = 0; i < legs.size() && blocked.empty(); ++i) {
    blocked = gate_.check_leg(from, legs[i], i == 0 ? "the climb" : i == 1 ? "the flight home" : "the descent");
    from = legs[i];
  }
  const nlohmann::json home_json = point_json(home);
  if (blocked.empty()) {
    cancel_route("return_to_home");
    const int32_t seq = send_fc(a3lcm::fc_command_t::RETURN_HOME, home, 0.0, kNoYaw);
    nlohmann::json extra = {{"route", "direct"},
                            {"home", home_json},
                            {"distance_m", rounded((home.head<2>() - p.head<2>()).norm(), 1)},
                            {"eta_s", rounded(gate_.energy().route_time_s(p, legs, speed), 1)}};
    await_status(seq, [this, extra](const a3lcm::fc_status_t* s) { answer_motion(s, extra); });
    return;
  }
  // The straight return crosses a no-fly zone: fly a detour at the return altitude, then land.
  std::string why;
  const auto plan = plan_path(gate_, p, home.head<2>(), legs.front().z(), config_.planner, &why);
  if (!plan) return finish_gate_refusal(blocked + "; no detour: " + why);
  const Eigen::Vector3d above_home = plan->waypoints.back();
  if (auto problem = gate_.check_descent(above_home); !problem.empty()) return finish_gate_refusal(problem);
  std::vector<RoutePoint> points;
  for (const auto& w : plan->waypoints) points.push_back(RoutePoint{w});
  nlohmann::json extra = {{"route", "detour"},
                          {"home", home_json},
                          {"avoids", plan->avoided},
                          {"waypoints", points.size()},
                          {"route_length_m", rounded(plan->length_m, 1)},
                          {"eta_s", rounded(gate_.energy().route_time_s(p, plan->waypoints, speed) +
                                                above_home.z() / gate_.energy().descent_speed_mps,
                                            1)}};
  start_route(OnboardRoute("return_to_home", std::move(points), speed, RouteEnd::kLand), std::move(extra));
}

void ToolServerNode::tool_adjust_speed(const nlohmann::json& args) {
  const double speed = args.at("speed_mps").get<double>();
  if (auto why = gate_.check_speed(speed); !why.empty()) return finish_gate_refusal(why);
  const int32_t seq = send_fc(a3lcm::fc_command_t::SET_SPEED, position().value_or(Eigen::Vector3d::Zero()), speed, kNoYaw);
  if (route_) route_->compatible_command_sent(seq);
  await_status(seq, [this, speed](const a3lcm::fc_status_t* s) {
    if (s != nullptr && s->last_command_accepted) {
      speed_mps_ = speed;
      if (route_) route_->set_speed_mps(speed);
    }
    answer_motion(s, {{"speed_mps", rounded(speed, 2)}});
  });
}

}  // namespace a3::agent
