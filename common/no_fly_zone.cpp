// No-fly zone geometry.
#include "common/no_fly_zone.hpp"

#include <algorithm>
#include <cmath>

namespace a3::common {

bool NoFlyZone::contains(const Eigen::Vector3d& p) const {
  if (!spans_altitude(p.z())) return false;
  return clearance_m(p.head<2>()) < 0.0;
}

double NoFlyZone::clearance_m(const Eigen::Vector2d& p) const {
  if (polygon.empty()) return (p - centre).norm() - radius_m;
  const double d = polygon_edge_distance(polygon, p);
  return polygon_contains(polygon, p) ? -d : d;
}

Eigen::Vector2d NoFlyZone::away_direction(const Eigen::Vector2d& p) const {
  Eigen::Vector2d nearest = centre;
  if (!polygon.empty()) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector2d q;
    for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
      const double d = segment_distance(p, polygon[j], polygon[i], &q);
      if (d < best) best = d, nearest = q;
    }
  }
  Eigen::Vector2d out = p - nearest;
  if (out.norm() < 1e-9) return Eigen::Vector2d::UnitX();
  out.normalize();
  // Inside a polygon the nearest edge point lies outward.
  return !polygon.empty() && polygon_contains(polygon, p) ? Eigen::Vector2d(-out) : out;
}

bool NoFlyZone::crossed_by(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double margin_m) const {
  // Altitude: the segment must reach the zone's vertical extent somewhere.
  if (std::max(a.z(), b.z()) < floor_m || std::min(a.z(), b.z()) > ceiling_m) return false;
  const Eigen::Vector2d a2 = a.head<2>(), b2 = b.head<2>();
  if (polygon.empty()) return segment_enters_circle(centre, radius_m + margin_m, a2, b2);
  if (segment_enters_polygon(polygon, a2, b2)) return true;
  if (margin_m <= 0.0) return false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    if (segment_distance(polygon[i], a2, b2) <= margin_m) return true;
    if (segment_distance(a2, polygon[j], polygon[i]) <= margin_m) return true;
    if (segment_distance(b2, polygon[j], polygon[i]) <= margin_m) return true;
  }
  return false;
}

}  // namespace a3::common
