// Polygon geofence.
#include "bridge/fc/geofence.hpp"

#include <limits>
#include <stdexcept>
#include <string>

#include "common/polygon.hpp"

namespace a3::bridge {

Geofence::Geofence(std::vector<Eigen::Vector2d> polygon, double min_altitude_m, double max_altitude_m)
    : polygon_(std::move(polygon)), min_altitude_m_(min_altitude_m), max_altitude_m_(max_altitude_m) {
  if (!polygon_.empty() && polygon_.size() < 3) {
    throw std::invalid_argument("a geofence polygon needs at least 3 vertices, got " +
                                std::to_string(polygon_.size()));
  }
  if (!(min_altitude_m < max_altitude_m)) {
    throw std::invalid_argument("altitude envelope: min " + std::to_string(min_altitude_m) +
                                " m must be below max " + std::to_string(max_altitude_m) + " m");
  }
}

bool Geofence::contains_xy(const Eigen::Vector2d& p) const {
  return !has_polygon() || common::polygon_contains(polygon_, p);
}

double Geofence::distance_to_edge_m(const Eigen::Vector2d& p) const {
  return has_polygon() ? common::polygon_edge_distance(polygon_, p) : std::numeric_limits<double>::infinity();
}

Eigen::Vector2d Geofence::outward_normal_near(const Eigen::Vector2d& p) const {
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  Eigen::Vector2d closest;
  for (std::size_t i = 0, j = polygon_.size() - 1; i < polygon_.size(); j = i++) {
    const double d = common::segment_distance(p, polygon_[j], polygon_[i], &closest);
    if (d < best) {
      best = d;
      const Eigen::Vector2d edge = polygon_[i] - polygon_[j];
      Eigen::Vector2d n(edge.y(), -edge.x());
      n.normalize();
      // Outward: away from a point just inside.
      if (contains_xy(closest + 0.01 * n)) n = -n;
      normal = n;
    }
  }
  return normal;
}

}  // namespace a3::bridge
