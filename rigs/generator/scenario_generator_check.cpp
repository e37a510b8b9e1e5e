// Flyability of a generated mission, with the rig's gate, planner, energy model and limits.
#include "rigs/generator/scenario_generator_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rigs/run/node_configs.hpp"
#include "vehicle/maneuvers.hpp"
#include "vehicle/path_planner.hpp"
#include "vehicle/safety_gate.hpp"

namespace a3::rigs {
namespace {

using agent::ObjectiveType;
using Points = std::vector<Eigen::Vector3d>;

constexpr double kBatteryMarginPct = 5.0;   // beyond the gate's reserve, for the wind
constexpr double kMinGroundSpeed_mps = 3.0; // progress into the wind the mission may count on

std::string text(const char* format, double a, double b = 0.0, double c = 0.0) {
  char out[256];
  std::snprintf(out, sizeof out, format, a, b, c);
  return out;
}

// Level flight at the tilt limit: the horizontal thrust m g tan(tilt) against linear and
// quadratic drag of the airframe with its payloads.
double max_airspeed_mps(const VehicleConfigs& c) {
  const auto& p = c.dynamics.params;
  const double force_N = p.total_mass_kg() * dynamics::kGravity_mps2 *
                         std::tan(c.fc.params.limits.max_tilt_deg * M_PI / 180.0);
  return dynamics::airspeed_for_drag_mps(p.aero, force_N);
}

struct RouteWalk {
  const vehicle::SafetyGate& gate;
  const vehicle::PlannerConfig& planner;
  Points points;         // every point flown after take-off, in order
  Eigen::Vector3d at;    // where the vehicle is
  std::string problem;

  // Around the zones, as path_plan routes it (the first leg and the way home).
  void plan_to(const Eigen::Vector2d& goal, double altitude_m, const std::string& what) {
    std::string why;
    const auto path = vehicle::plan_path(gate, at, goal, altitude_m, planner, &why);
    if (!path) {
      problem = what + ": no route around the no-fly zones: " + why;
      return;
    }
    points.insert(points.end(), path->waypoints.begin(), path->waypoints.end());
    at = points.back();
  }
  // Straight, as an agent flies a set_waypoint or a route.
  void fly_to(const Points& route, const std::string& what) {
    if (const std::string why = gate.check_path(at, route); !why.empty()) {
      problem = what + ": " + why;
      return;
    }
    points.insert(points.end(), route.begin(), route.end());
    at = points.back();
  }
};

Eigen::Vector2d anchor_of(const agent::Objective& o) {
  const bool area = o.type == ObjectiveType::kSurvey || o.type == ObjectiveType::kThermalSearch;
  return area ? o.area.front() : o.point;
}

void fly_objective(RouteWalk& walk, const agent::Objective& o, double cruise_m, bool first) {
  const Eigen::Vector2d anchor = anchor_of(o);
  if (first) {
    walk.plan_to(anchor, cruise_m, "the way to " + o.id);
  } else {
    walk.fly_to({{anchor.x(), anchor.y(), cruise_m}}, "the leg to " + o.id);
  }
  if (!walk.problem.empty()) return;
  switch (o.type) {
    case ObjectiveType::kSurvey:
    case ObjectiveType::kThermalSearch:
      walk.fly_to(vehicle::survey_waypoints(o.area, reference_spacing_m(o), o.altitude_m, walk.at.head<2>(), 200).waypoints,
                  o.id + "'s lawnmower");
      break;
    case ObjectiveType::kImagePoint:
      walk.fly_to({{o.point.x(), o.point.y(), o.altitude_m}}, o.id);
      break;
    case ObjectiveType::kDelivery:
      walk.fly_to({{o.point.x(), o.point.y(), std::max(2.0, o.drop_altitude_m - 3.0)}}, o.id + "'s drop");
      break;
    case ObjectiveType::kReturnAndLand:
      break;
  }
}

MissionCheck with_problem(MissionCheck m, const std::string& problem) {
  m.problem = problem;
  return m;
}

// How many of `points` are flown up to the first one (from `from` on) above `anchor`.
std::size_t points_to(const Points& points, std::size_t from, const Eigen::Vector2d& anchor) {
  for (std::size_t i = from; i < points.size(); ++i) {
    if ((points[i].head<2>() - anchor).norm() < 1e-6) return i + 1;
  }
  return points.size();
}

std::string wind_problem(const Scenario& s, const MissionCheck& m) {
  const double wind = s.start.env.wind_mps;
  const double gust = s.start.env.gust_mps.value_or(wind);
  if (m.max_airspeed_mps - wind < kMinGroundSpeed_mps || gust > 0.9 * m.max_airspeed_mps) {
    return text("wind %.1f m/s gusting %.1f m/s is more than the airframe can fly (top airspeed %.1f m/s at the "
                "tilt limit)", wind, gust, m.max_airspeed_mps);
  }
  return "";
}

}  // namespace

double reference_spacing_m(const agent::Objective& o) {
  return o.type == ObjectiveType::kThermalSearch ? std::max(10.0, 1.6 * o.radius_m) : 30.0;
}

MissionCheck check_generated_mission(const Scenario& s) {
  RunOptions options;
  options.runtime = Runtime::kVirtual;
  const VehicleConfigs c = make_vehicle_configs(s, options, 0);
  const vehicle::ToolServerConfig& t = c.tool_server;
  MissionCheck m;
  m.max_airspeed_mps = max_airspeed_mps(c);
  const double wind = s.start.env.wind_mps;
  m.ground_speed_mps = std::min(s.mission.cruise_speed_mps, m.max_airspeed_mps - wind);
  if (m.problem = wind_problem(s, m); !m.problem.empty()) return m;

  const vehicle::SafetyGate gate(t.airspace, t.gate, t.energy, t.home_W_m);
  RouteWalk walk{gate, t.planner, {}, t.home_W_m, ""};
  bool first = true;
  std::size_t first_objective_points = 0;  // the points up to the first objective's anchor
  for (const auto& o : s.mission.objectives) {
    if (o.type == ObjectiveType::kReturnAndLand) continue;
    const std::size_t before = walk.points.size();
    fly_objective(walk, o, s.mission.cruise_altitude_m, first);
    if (first) first_objective_points = points_to(walk.points, before, anchor_of(o));
    first = false;
    if (!walk.problem.empty()) return with_problem(m, walk.problem);
  }
  const Points outbound = walk.points;
  const double return_z = std::clamp(std::max(walk.at.z(), t.gate.return_altitude_m), t.airspace.min_altitude_m,
                                     t.airspace.max_altitude_m);
  walk.plan_to(t.home_W_m.head<2>(), return_z, "the way home");
  if (!walk.problem.empty()) return with_problem(m, walk.problem);
  walk.points.push_back(t.home_W_m);

  const vehicle::BatteryEstimate battery = gate.estimate_battery(t.home_W_m, outbound, m.ground_speed_mps, 100.0);
  m.battery_left_pct = battery.left_pct;
  if (battery.left_pct < t.gate.battery_reserve_pct + kBatteryMarginPct) {
    m.problem = text("battery: the mission needs about %.0f %% and the way home %.0f %%, leaving %.0f %%",
                     battery.route_pct, battery.return_pct, battery.left_pct);
    return m;
  }
  m.route_time_s = t.energy.route_time_s(t.home_W_m, walk.points, m.ground_speed_mps);
  const Eigen::Vector3d top_of_climb(t.home_W_m.x(), t.home_W_m.y(), s.mission.cruise_altitude_m);
  m.phases.transit_s = t.energy.route_time_s(t.home_W_m, {top_of_climb}, m.ground_speed_mps);
  m.phases.objective_s = t.energy.route_time_s(
      t.home_W_m, Points(outbound.begin(), outbound.begin() + static_cast<std::ptrdiff_t>(first_objective_points)),
      m.ground_speed_mps);
  m.phases.home_s = t.energy.route_time_s(t.home_W_m, outbound, m.ground_speed_mps);
  return m;
}

}  // namespace a3::rigs
