// Motion tools that fly one target or change how the vehicle flies: takeoff, set_waypoint,
// set_altitude, navigate_to, adjust_speed, hold, land. Gate checks, then an fc command or an
// onboard route; each answers once the fc's status for its command arrives (or the wait
// times out). ETAs are at the ground speed made good in the estimated wind (the energy
// model's), and name that wind.
#include <algorithm>
#include <cmath>

#include "vehicle/motion_steps.hpp"
#include "vehicle/observation_json.hpp"
#include "vehicle/vehicle_tools.hpp"

namespace a3::vehicle {
namespace {

Eigen::Vector3d point3(const nlohmann::json& a) {
  return Eigen::Vector3d(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
}

void takeoff(VehicleServices& vehicle, const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(vehicle, &p, &battery)) return;
  const SafetyGate& gate = vehicle.gate();
  const double altitude_m = args.at("altitude_m").get<double>();
  const Eigen::Vector3d target(p.x(), p.y(), altitude_m);
  std::string why = gate.check_target(target, "take-off target");
  if (why.empty()) why = gate.check_leg(p, target, "climb");
  if (why.empty()) why = gate.check_battery(p, {target}, vehicle.speed_mps(), battery);
  if (!why.empty()) return vehicle.finish_gate_refusal(why);
  vehicle.cancel_route("superseded by takeoff");
  const int32_t seq = vehicle.send_fc(a3lcm::fc_command_t::TAKEOFF, target, 0.0, kNoYaw);
  const double eta_s = std::abs(altitude_m - p.z()) / gate.energy().climb_speed_mps;
  vehicle.await_status(seq, [&vehicle, target, altitude_m, eta_s](const a3lcm::fc_status_t* s) {
    if (s != nullptr && s->last_command_accepted) vehicle.set_takeoff_target(target);
    answer_motion(vehicle, s, {{"target_altitude_m", rounded(altitude_m, 1)}, {"eta_s", rounded(eta_s, 1)}});
  });
}

void set_waypoint(VehicleServices& vehicle, const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(vehicle, &p, &battery)) return;
  const Eigen::Vector3d target(args.at("x").get<double>(), args.at("y").get<double>(), args.at("z").get<double>());
  const double speed = args.contains("speed_mps") ? args["speed_mps"].get<double>() : vehicle.speed_mps();
  if (auto why = vehicle.gate().check_route(p, {target}, speed, battery); !why.empty()) {
    return vehicle.finish_gate_refusal(why);
  }
  const double eta_s = vehicle.gate().energy().leg_time_s(p, target, speed);
  start_route(vehicle, OnboardRoute("set_waypoint", {RoutePoint{target}}, speed, RouteEnd::kHold),
              {{"target", point_json(target)},
               {"distance_m", rounded((target - p).norm(), 1)},
               {"speed_mps", rounded(speed, 2)},
               {"eta_s", rounded(eta_s, 1)},
               {"wind", wind_estimate_json(vehicle.wind_estimate())}});
}

void set_altitude(VehicleServices& vehicle, const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(vehicle, &p, &battery)) return;
  const double speed = vehicle.speed_mps();
  const Eigen::Vector3d target(p.x(), p.y(), args.at("z").get<double>());
  if (auto why = vehicle.gate().check_route(p, {target}, speed, battery); !why.empty()) {
    return vehicle.finish_gate_refusal(why);
  }
  const double eta_s = vehicle.gate().energy().leg_time_s(p, target, speed);
  start_route(vehicle, OnboardRoute("set_altitude", {RoutePoint{target}}, speed, RouteEnd::kHold),
              {{"target", point_json(target)}, {"eta_s", rounded(eta_s, 1)}});
}

void navigate_to(VehicleServices& vehicle, const nlohmann::json& args) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(vehicle, &p, &battery)) return;
  const auto& list = args.at("waypoints");
  const std::size_t max_waypoints = vehicle.config().route.max_waypoints;
  if (list.size() > max_waypoints) {
    return vehicle.finish_error("args/waypoints: " + std::to_string(list.size()) + " waypoints, more than the " +
                                std::to_string(max_waypoints) + " a route may have");
  }
  std::vector<RoutePoint> points;
  for (const auto& w : list) points.push_back(RoutePoint{point3(w)});
  const double speed = args.contains("speed_mps") ? args["speed_mps"].get<double>() : vehicle.speed_mps();
  const auto targets = positions(points);
  if (auto why = vehicle.gate().check_route(p, targets, speed, battery); !why.empty()) {
    return vehicle.finish_gate_refusal(why);
  }
  const double eta_s = vehicle.gate().energy().route_time_s(p, targets, speed);
  const double length = route_length_m(p, targets);
  start_route(vehicle, OnboardRoute("navigate_to", std::move(points), speed, RouteEnd::kHold),
              {{"waypoints", targets.size()},
               {"first_target", point_json(targets.front())},
               {"route_length_m", rounded(length, 1)},
               {"speed_mps", rounded(speed, 2)},
               {"eta_s", rounded(eta_s, 1)},
               {"wind", wind_estimate_json(vehicle.wind_estimate())}});
}

void adjust_speed(VehicleServices& vehicle, const nlohmann::json& args) {
  const double speed = args.at("speed_mps").get<double>();
  if (auto why = vehicle.gate().check_speed(speed); !why.empty()) return vehicle.finish_gate_refusal(why);
  const Eigen::Vector3d p = vehicle.position().value_or(Eigen::Vector3d::Zero());
  const int32_t seq = vehicle.send_fc(a3lcm::fc_command_t::SET_SPEED, p, speed, kNoYaw);
  if (OnboardRoute* route = vehicle.onboard_route()) route->compatible_command_sent(seq);
  vehicle.await_status(seq, [&vehicle, speed](const a3lcm::fc_status_t* s) {
    if (s != nullptr && s->last_command_accepted) {
      vehicle.set_speed_mps(speed);
      if (OnboardRoute* route = vehicle.onboard_route()) route->set_speed_mps(speed);
    }
    answer_motion(vehicle, s, {{"speed_mps", rounded(speed, 2)}});
  });
}

void hold(VehicleServices& vehicle, const nlohmann::json&) {
  vehicle.cancel_route("hold");
  const Eigen::Vector3d p = vehicle.position().value_or(Eigen::Vector3d::Zero());
  const int32_t seq = vehicle.send_fc(a3lcm::fc_command_t::HOLD, p, 0.0, kNoYaw);
  vehicle.await_status(seq, [&vehicle](const a3lcm::fc_status_t* s) {
    answer_motion(vehicle, s, nlohmann::json::object());
  });
}

void land(VehicleServices& vehicle, const nlohmann::json&) {
  Eigen::Vector3d p;
  double battery = 0.0;
  if (!require_telemetry(vehicle, &p, &battery)) return;  // landing is never refused for the battery
  if (auto why = vehicle.gate().check_descent(p); !why.empty()) return vehicle.finish_gate_refusal(why);
  vehicle.cancel_route("land");
  const int32_t seq = vehicle.send_fc(a3lcm::fc_command_t::LAND, p, 0.0, kNoYaw);
  const double eta_s = std::max(p.z(), 0.0) / vehicle.gate().energy().descent_speed_mps;
  vehicle.await_status(seq, [&vehicle, eta_s](const a3lcm::fc_status_t* s) {
    answer_motion(vehicle, s, {{"eta_s", rounded(eta_s, 1)}});
  });
}

}  // namespace

void add_motion_tools(ToolHandlers& handlers) {
  handlers.add_tool("takeoff", takeoff);
  handlers.add_tool("set_waypoint", set_waypoint);
  handlers.add_tool("set_altitude", set_altitude);
  handlers.add_tool("navigate_to", navigate_to);
  handlers.add_tool("adjust_speed", adjust_speed);
  handlers.add_tool("hold", hold);
  handlers.add_tool("land", land);
}

}  // namespace a3::vehicle
