// A no-fly zone: a vertical prism over a polygon, or a cylinder, between a floor and a
// ceiling, in local ENU metres. The one geometry the flight controller's keep-out brake, the
// tool server's safety gate and planner, and the airspace monitor all measure with.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <string>

#include "common/polygon.hpp"

namespace a3::common {

struct NoFlyZone {
  std::string id;
  Polygon2d polygon;      // empty: a cylinder
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
  double floor_m = -std::numeric_limits<double>::infinity();
  double ceiling_m = std::numeric_limits<double>::infinity();

  bool contains(const Eigen::Vector3d& p) const;
  // Whether altitude z_m lies between floor and ceiling widened by margin_m.
  bool spans_altitude(double z_m, double margin_m = 0.0) const {
    return z_m >= floor_m - margin_m && z_m <= ceiling_m + margin_m;
  }
  // Horizontal distance to the zone's boundary: positive outside, negative inside.
  double clearance_m(const Eigen::Vector2d& p) const;
  // The horizontal unit vector along which the clearance grows fastest at p (away from the
  // zone); for a point on the boundary or at a cylinder's centre, some unit vector.
  Eigen::Vector2d away_direction(const Eigen::Vector2d& p) const;
  // Whether the straight segment a→b passes through the zone (horizontally within `margin_m`
  // of it, at an altitude between floor and ceiling somewhere along the segment).
  bool crossed_by(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double margin_m = 0.0) const;
};

}  // namespace a3::common
