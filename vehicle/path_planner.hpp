// Routes around no-fly zones for the ground station's path_plan: the shortest path on a
// visibility graph whose nodes are the start, the goal and points around each zone that
// reaches the planning altitude (a circle's circumscribed polygon, a polygon's vertices pushed
// out), clearance_m beyond the gate's margin. Every leg of the graph must pass the gate's
// leg check and every node its target check, so the route passes the same gate as flying it.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "vehicle/safety_gate.hpp"

namespace a3::vehicle {

struct PlannerConfig {
  double clearance_m = 3.0;   // beyond the gate's no-fly-zone margin
  int circle_vertices = 16;   // polygon approximating each cylinder zone (≥ 6)

  void validate(const std::string& where) const;
};

struct PlannedPath {
  std::vector<Eigen::Vector3d> waypoints;  // excluding the start; the last is the goal
  double length_m = 0.0;                   // from the start
  std::vector<std::string> avoided;        // zones whose corners the route uses
};

// The route from start to goal_xy at altitude_m (a first vertical move when the start is at
// another altitude), or nothing with *why set.
std::optional<PlannedPath> plan_path(const SafetyGate& gate, const Eigen::Vector3d& start_W_m,
                                     const Eigen::Vector2d& goal_xy, double altitude_m, const PlannerConfig& config,
                                     std::string* why);

}  // namespace a3::vehicle
