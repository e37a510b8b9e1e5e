// Orbit and survey patterns.
#include "vehicle/maneuvers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace a3::vehicle {
namespace {

double signed_area(const common::Polygon2d& p) {
  double a = 0.0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return 0.5 * a;
}

using Interval = std::pair<double, double>;  // along-line coordinates, low to high

std::vector<Interval> line_intervals(const common::Polygon2d& uv, double c) {
  std::vector<double> cuts;
  for (std::size_t i = 0, j = uv.size() - 1; i < uv.size(); j = i++) {
    const Eigen::Vector2d& p = uv[j];
    const Eigen::Vector2d& q = uv[i];
    if ((p.y() > c) != (q.y() > c)) cuts.push_back(p.x() + (c - p.y()) * (q.x() - p.x()) / (q.y() - p.y()));
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<Interval> out;
  for (std::size_t k = 0; k + 1 < cuts.size(); k += 2) {
    if (cuts[k + 1] - cuts[k] > 1e-6) out.emplace_back(cuts[k], cuts[k + 1]);
  }
  return out;
}

}  // namespace

std::vector<Eigen::Vector3d> orbit_waypoints(const Eigen::Vector2d& centre, double radius_m, double altitude_m,
                                             const Eigen::Vector2d& from_xy, double max_chord_m) {
  const double circumference = 2.0 * M_PI * radius_m;
  const int n = std::clamp(static_cast<int>(std::ceil(circumference / std::max(max_chord_m, 1e-3))), 8, 360);
  const Eigen::Vector2d d = from_xy - centre;
  const double a0 = d.norm() > 1e-9 ? std::atan2(d.y(), d.x()) : 0.0;
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + 2.0 * M_PI * k / n;
    out.emplace_back(centre.x() + radius_m * std::cos(a), centre.y() + radius_m * std::sin(a), altitude_m);
  }
  return out;
}

SurveyPattern survey_waypoints(const common::Polygon2d& area, double spacing_m, double altitude_m,
                               const Eigen::Vector2d& from_xy, std::size_t max_waypoints) {
  if (area.size() < 3 || std::abs(signed_area(area)) < 1.0) {
    throw std::invalid_argument("area: the polygon must have at least 3 vertices and an area of at least 1 m^2");
  }
  if (!(spacing_m > 0.0)) throw std::invalid_argument("spacing_m: must be > 0");
  Eigen::Vector2d lo = area.front(), hi = area.front();
  for (const auto& p : area) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Work in (u along the lines, v across them).
  const bool along_x = (hi.x() - lo.x()) >= (hi.y() - lo.y());
  const auto to_uv = [&](const Eigen::Vector2d& p) { return along_x ? p : Eigen::Vector2d(p.y(), p.x()); };
  const auto to_xy = [&](double u, double v) { return along_x ? Eigen::Vector2d(u, v) : Eigen::Vector2d(v, u); };
  common::Polygon2d uv;
  for (const auto& p : area) uv.push_back(to_uv(p));
  const double v_lo = along_x ? lo.y() : lo.x();
  const double extent = along_x ? hi.y() - lo.y() : hi.x() - lo.x();
  const std::size_t n_lines = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(extent / spacing_m - 1e-9)));
  if (2 * n_lines > max_waypoints) {
    throw std::invalid_argument("spacing_m: " + std::to_string(n_lines) + " lines of " + std::to_string(spacing_m) +
                                " m spacing need more than the " + std::to_string(max_waypoints) +
                                " waypoints a route may have; widen the spacing");
  }
  std::vector<std::pair<double, std::vector<Interval>>> lines;
  for (std::size_t k = 0; k < n_lines; ++k) {
    const double v = v_lo + (static_cast<double>(k) + 0.5) * extent / static_cast<double>(n_lines);
    auto intervals = line_intervals(uv, v);
    if (!intervals.empty()) lines.emplace_back(v, std::move(intervals));
  }
  // Four ways to fly it (first line from either side, each end first): take the one that
  // begins nearest to from_xy.
  SurveyPattern best;
  double best_d = std::numeric_limits<double>::infinity();
  for (int variant = 0; variant < 4; ++variant) {
    const bool reverse_lines = variant & 1;
    bool ascending = (variant & 2) == 0;
    SurveyPattern s;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const auto& [v, intervals] = lines[reverse_lines ? lines.size() - 1 - i : i];
      std::vector<Interval> ordered = intervals;
      if (!ascending) {
        std::reverse(ordered.begin(), ordered.end());
        for (auto& iv : ordered) std::swap(iv.first, iv.second);
      }
      for (const auto& [a, b] : ordered) {
        const Eigen::Vector2d pa = to_xy(a, v), pb = to_xy(b, v);
        s.waypoints.emplace_back(pa.x(), pa.y(), altitude_m);
        s.waypoints.emplace_back(pb.x(), pb.y(), altitude_m);
        s.line_length_m += std::abs(b - a);
      }
      ascending = !ascending;
      ++s.lines;
    }
    if (s.waypoints.size() > max_waypoints) {
      throw std::invalid_argument("spacing_m: the survey needs " + std::to_string(s.waypoints.size()) +
                                  " waypoints, more than the " + std::to_string(max_waypoints) +
                                  " a route may have; widen the spacing");
    }
    if (s.waypoints.empty()) continue;
    const double d = (s.waypoints.front().head<2>() - from_xy).norm();
    if (d < best_d - 1e-9) {
      best_d = d;
      best = std::move(s);
    }
  }
  if (best.waypoints.empty()) throw std::invalid_argument("area: no survey line crosses the polygon");
  return best;
}

}  // namespace a3::vehicle
