// The airspace of a scenario as the rig enforces and measures it: the geofence polygon and
// altitude envelope (from the corpus' initial_state), no-fly zones (cylinders or polygons with
// a floor and ceiling) and the planned paths of other aircraft (swarm peers), all in local ENU
// metres.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <string>
#include <vector>

#include "common/no_fly_zone.hpp"
#include "common/polygon.hpp"

namespace a3::agent {

// The zone geometry is shared with the flight controller (common/no_fly_zone.hpp).
using NoFlyZone = common::NoFlyZone;

struct TrafficWaypoint {
  double t_s = 0.0;
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
};

// Another aircraft's plan: positions at times, straight lines between them, holding at the
// last one.
struct TrafficPlan {
  std::string id;
  std::vector<TrafficWaypoint> path;   // t_s increasing
  double min_separation_m = 30.0;      // closer than this to our vehicle is a breach
  bool yields_when_asked = true;       // answers an A2A collision_avoidance by climbing away
  double yield_climb_m = 40.0;
  double conflict_deadline_s = 0.0;    // > 0: the scenario expects a negotiation by this time

  Eigen::Vector3d position_at(double t_s) const;
  Eigen::Vector3d velocity_at(double t_s) const;
};

struct Airspace {
  common::Polygon2d geofence;  // empty: unbounded
  double min_altitude_m = 0.0;
  double max_altitude_m = std::numeric_limits<double>::infinity();
  std::vector<NoFlyZone> no_fly_zones;
  std::vector<TrafficPlan> traffic;

  bool inside_geofence(const Eigen::Vector2d& p) const;
  double geofence_clearance_m(const Eigen::Vector2d& p) const;  // negative outside
  bool altitude_ok(double z_m) const { return z_m >= min_altitude_m && z_m <= max_altitude_m; }
  // The first no-fly zone containing p, or nullptr.
  const NoFlyZone* zone_containing(const Eigen::Vector3d& p) const;
};

}  // namespace a3::agent
