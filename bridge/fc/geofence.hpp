// The airspace the flight controller enforces: a horizontal polygon (the scenario's geofence,
// ENU metres) and an altitude envelope. Containment, distance to the boundary, and the point
// inside nearest to a point outside.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace a3::bridge {

class Geofence {
 public:
  Geofence() = default;  // no polygon: unbounded horizontally
  // polygon: vertices in order (either orientation), at least 3; altitudes min < max.
  Geofence(std::vector<Eigen::Vector2d> polygon, double min_altitude_m, double max_altitude_m);

  bool has_polygon() const { return polygon_.size() >= 3; }
  bool contains_xy(const Eigen::Vector2d& p) const;
  // Distance from an inside point to the polygon's edges (infinite without a polygon).
  double distance_to_edge_m(const Eigen::Vector2d& p) const;
  // The unit outward normal of the nearest edge to p.
  Eigen::Vector2d outward_normal_near(const Eigen::Vector2d& p) const;
  bool altitude_ok(double z_m) const { return z_m >= min_altitude_m_ && z_m <= max_altitude_m_; }
  double min_altitude_m() const { return min_altitude_m_; }
  double max_altitude_m() const { return max_altitude_m_; }

 private:
  std::vector<Eigen::Vector2d> polygon_;
  double min_altitude_m_ = -1e9;
  double max_altitude_m_ = 1e9;
};

}  // namespace a3::bridge
