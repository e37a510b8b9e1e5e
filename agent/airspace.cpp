// Airspace geometry.
#include "agent/airspace.hpp"

#include <algorithm>
#include <cmath>

namespace a3::agent {

Eigen::Vector3d TrafficPlan::position_at(double t) const {
  if (path.empty()) return Eigen::Vector3d::Zero();
  if (t <= path.front().t_s) return path.front().p_W_m;
  for (std::size_t i = 1; i < path.size(); ++i) {
    if (t <= path[i].t_s) {
      const double span = path[i].t_s - path[i - 1].t_s;
      const double f = span > 0.0 ? (t - path[i - 1].t_s) / span : 1.0;
      return path[i - 1].p_W_m + f * (path[i].p_W_m - path[i - 1].p_W_m);
    }
  }
  return path.back().p_W_m;
}

Eigen::Vector3d TrafficPlan::velocity_at(double t) const {
  for (std::size_t i = 1; i < path.size(); ++i) {
    if (t >= path[i - 1].t_s && t < path[i].t_s) {
      const double span = path[i].t_s - path[i - 1].t_s;
      return span > 0.0 ? Eigen::Vector3d((path[i].p_W_m - path[i - 1].p_W_m) / span) : Eigen::Vector3d::Zero();
    }
  }
  return Eigen::Vector3d::Zero();
}

bool Airspace::inside_geofence(const Eigen::Vector2d& p) const {
  return geofence.size() < 3 || common::polygon_contains(geofence, p);
}

double Airspace::geofence_clearance_m(const Eigen::Vector2d& p) const {
  if (geofence.size() < 3) return std::numeric_limits<double>::infinity();
  const double d = common::polygon_edge_distance(geofence, p);
  return common::polygon_contains(geofence, p) ? d : -d;
}

const NoFlyZone* Airspace::zone_containing(const Eigen::Vector3d& p) const {
  for (const auto& z : no_fly_zones) {
    if (z.contains(p)) return &z;
  }
  return nullptr;
}

}  // namespace a3::agent
