// Plane geometry.
#include "common/polygon.hpp"

#include <algorithm>
#include <limits>

namespace a3::common {

bool polygon_contains(const Polygon2d& polygon, const Eigen::Vector2d& p) {
  if (polygon.size() < 3) return false;
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        Eigen::Vector2d* nearest) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  const Eigen::Vector2d q = a + t * ab;
  if (nearest != nullptr) *nearest = q;
  return (p - q).norm();
}

double polygon_edge_distance(const Polygon2d& polygon, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  if (polygon.size() < 2) return best;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    best = std::min(best, segment_distance(p, polygon[j], polygon[i]));
  }
  return best;
}

namespace {
double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}
bool on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
         p.y() <= std::max(a.y(), b.y());
}
}  // namespace

bool segments_intersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                        const Eigen::Vector2d& d) {
  const double d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && on_segment(c, d, a)) || (d2 == 0 && on_segment(c, d, b)) || (d3 == 0 && on_segment(a, b, c)) ||
         (d4 == 0 && on_segment(a, b, d));
}

bool segment_enters_polygon(const Polygon2d& polygon, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  if (polygon.size() < 3) return false;
  if (polygon_contains(polygon, a) || polygon_contains(polygon, b)) return true;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    if (segments_intersect(a, b, polygon[j], polygon[i])) return true;
  }
  return false;
}

bool segment_enters_circle(const Eigen::Vector2d& centre, double radius, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  return segment_distance(centre, a, b) <= radius;
}

}  // namespace a3::common
