// Waypoints of the named patterns of execute_maneuver: an orbit (one full circle) and a
// survey (a lawnmower over a polygon). Pure geometry; the gate checks the result.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

#include "common/polygon.hpp"

namespace a3::vehicle {

// One loop counter-clockwise around centre at altitude z, starting (and ending) at the circle
// point nearest to from_xy, with chords of at most max_chord_m (at least 8 of them).
std::vector<Eigen::Vector3d> orbit_waypoints(const Eigen::Vector2d& centre, double radius_m, double altitude_m,
                                             const Eigen::Vector2d& from_xy, double max_chord_m);

struct SurveyPattern {
  std::vector<Eigen::Vector3d> waypoints;  // line ends, in flying order
  std::size_t lines = 0;
  double line_length_m = 0.0;  // summed length of the lines (not the turns)
};

// Lines `spacing_m` apart (the first half a spacing in from the edge) parallel to the longer
// side of the area's bounding box, flown alternately, each covering every stretch of the line
// inside the polygon; begins at the line end nearest to from_xy. Throws std::invalid_argument
// (naming "area" or "spacing_m") for a degenerate area or more than max_waypoints line ends.
SurveyPattern survey_waypoints(const common::Polygon2d& area, double spacing_m, double altitude_m,
                               const Eigen::Vector2d& from_xy, std::size_t max_waypoints);

}  // namespace a3::vehicle
