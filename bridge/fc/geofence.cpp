// Polygon geofence.
#include "bridge/fc/geofence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace a3::bridge {
namespace {

// Distance from p to segment ab, and the closest point.
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        Eigen::Vector2d* closest) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  *closest = a + t * ab;
  return (p - *closest).norm();
}

}  // namespace

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
  if (!has_polygon()) return true;
  bool inside = false;
  for (std::size_t i = 0, j = polygon_.size() - 1; i < polygon_.size(); j = i++) {
    const Eigen::Vector2d& a = polygon_[i];
    const Eigen::Vector2d& b = polygon_[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

double Geofence::distance_to_edge_m(const Eigen::Vector2d& p) const {
  if (!has_polygon()) return std::numeric_limits<double>::infinity();
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d closest;
  for (std::size_t i = 0, j = polygon_.size() - 1; i < polygon_.size(); j = i++) {
    best = std::min(best, segment_distance(p, polygon_[j], polygon_[i], &closest));
  }
  return best;
}

Eigen::Vector2d Geofence::outward_normal_near(const Eigen::Vector2d& p) const {
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  Eigen::Vector2d closest;
  for (std::size_t i = 0, j = polygon_.size() - 1; i < polygon_.size(); j = i++) {
    const double d = segment_distance(p, polygon_[j], polygon_[i], &closest);
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
