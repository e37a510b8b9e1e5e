// Plane geometry for airspace rules: point in polygon, distance to a polygon's edges or a
// segment, and whether a segment crosses a polygon or a circle.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace a3::common {

using Polygon2d = std::vector<Eigen::Vector2d>;

// Even-odd rule; vertices in either orientation. False for fewer than 3 vertices.
bool polygon_contains(const Polygon2d& polygon, const Eigen::Vector2d& p);
// Distance to the nearest edge (infinite for fewer than 2 vertices).
double polygon_edge_distance(const Polygon2d& polygon, const Eigen::Vector2d& p);
// Distance from p to segment ab, and the nearest point of the segment.
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        Eigen::Vector2d* nearest = nullptr);
// Whether segments ab and cd intersect (touching counts).
bool segments_intersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                        const Eigen::Vector2d& d);
// Whether segment ab enters the polygon (an end inside, or crossing an edge).
bool segment_enters_polygon(const Polygon2d& polygon, const Eigen::Vector2d& a, const Eigen::Vector2d& b);
// Whether segment ab comes within radius of centre.
bool segment_enters_circle(const Eigen::Vector2d& centre, double radius, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b);

}  // namespace a3::common
