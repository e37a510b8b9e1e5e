// Airspace geometry.
#include "agent/airspace.hpp"

#include <algorithm>
#include <cmath>

namespace a3::agent {

bool NoFlyZone::contains(const Eigen::Vector3d& p) const {
  if (p.z() < floor_m || p.z() > ceiling_m) return false;
  return clearance_m(p.head<2>()) < 0.0;
}

double NoFlyZone::clearance_m(const Eigen::Vector2d& p) const {
  if (polygon.empty()) return (p - centre).norm() - radius_m;
  const double d = common::polygon_edge_distance(polygon, p);
  return common::polygon_contains(polygon, p) ? -d : d;
}

bool NoFlyZone::crossed_by(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double margin_m) const {
  // Altitude: the segment must reach the zone's vertical extent somewhere.
  if (std::max(a.z(), b.z()) < floor_m || std::min(a.z(), b.z()) > ceiling_m) return false;
  const Eigen::Vector2d a2 = a.head<2>(), b2 = b.head<2>();
  if (polygon.empty()) return common::segment_enters_circle(centre, radius_m + margin_m, a2, b2);
  if (common::segment_enters_polygon(polygon, a2, b2)) return true;
  if (margin_m <= 0.0) return false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    if (common::segment_distance(polygon[i], a2, b2) <= margin_m) return true;
    if (common::segment_distance(a2, polygon[j], polygon[i]) <= margin_m) return true;
    if (common::segment_distance(b2, polygon[j], polygon[i]) <= margin_m) return true;
  }
  return false;
}

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
