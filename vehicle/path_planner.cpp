// Visibility-graph planning around no-fly zones.
#include "vehicle/path_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>

namespace a3::vehicle {
namespace {

struct GraphNode {
  Eigen::Vector3d p;
  std::string zone;  // "" for the start and the goal
};

double signed_area(const common::Polygon2d& p) {
  double a = 0.0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return 0.5 * a;
}

// Points around the zone, `offset_m` outside its boundary.
std::vector<Eigen::Vector2d> corners(const NoFlyZone& zone, double offset_m, int circle_vertices) {
  std::vector<Eigen::Vector2d> out;
  if (zone.polygon.empty()) {
    const double r = (zone.radius_m + offset_m) / std::cos(M_PI / circle_vertices);
    for (int k = 0; k < circle_vertices; ++k) {
      const double a = 2.0 * M_PI * k / circle_vertices;
      out.push_back(zone.centre + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    return out;
  }
  const auto& poly = zone.polygon;
  const double orientation = signed_area(poly) >= 0.0 ? 1.0 : -1.0;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& prev = poly[(i + n - 1) % n];
    const Eigen::Vector2d& here = poly[i];
    const Eigen::Vector2d& next = poly[(i + 1) % n];
    const Eigen::Vector2d e1 = here - prev, e2 = next - here;
    if (e1.norm() < 1e-9 || e2.norm() < 1e-9) continue;
    const Eigen::Vector2d n1 = orientation * Eigen::Vector2d(e1.y(), -e1.x()).normalized();
    const Eigen::Vector2d n2 = orientation * Eigen::Vector2d(e2.y(), -e2.x()).normalized();
    Eigen::Vector2d bisector = n1 + n2;
    if (bisector.norm() < 1e-9) bisector = n1;
    bisector.normalize();
    out.push_back(here + bisector * (offset_m / std::max(bisector.dot(n1), 0.2)));
  }
  return out;
}

}  // namespace

void PlannerConfig::validate(const std::string& where) const {
  if (!std::isfinite(clearance_m) || clearance_m < 0.0) {
    throw std::invalid_argument(where + ".clearance_m must be a finite number >= 0, got " + std::to_string(clearance_m));
  }
  if (circle_vertices < 6 || circle_vertices > 128) {
    throw std::invalid_argument(where + ".circle_vertices must be in [6, 128], got " + std::to_string(circle_vertices));
  }
}

std::optional<PlannedPath> plan_path(const SafetyGate& gate, const Eigen::Vector3d& start, const Eigen::Vector2d& goal_xy,
                                     double altitude_m, const PlannerConfig& config, std::string* why) {
  const Eigen::Vector3d goal(goal_xy.x(), goal_xy.y(), altitude_m);
  if (auto problem = gate.check_target(goal, "goal"); !problem.empty()) {
    *why = problem;
    return std::nullopt;
  }
  std::vector<Eigen::Vector3d> prefix;
  const Eigen::Vector3d first(start.x(), start.y(), altitude_m);
  if (std::abs(start.z() - altitude_m) > 0.5) {
    if (auto problem = gate.check_leg(start, first, "the climb or descent to the planning altitude");
        !problem.empty()) {
      *why = problem;
      return std::nullopt;
    }
    prefix.push_back(first);
  }
  std::vector<GraphNode> nodes = {{first, ""}, {goal, ""}};
  const double offset_m = gate.config().nfz_margin_m + config.clearance_m;
  const double vmargin = gate.config().nfz_vertical_margin_m;
  for (const auto& zone : gate.airspace().no_fly_zones) {
    if (altitude_m < zone.floor_m - vmargin || altitude_m > zone.ceiling_m + vmargin) continue;
    for (const auto& c : corners(zone, offset_m, config.circle_vertices)) {
      const Eigen::Vector3d p(c.x(), c.y(), altitude_m);
      if (gate.check_target(p, "corner").empty()) nodes.push_back({p, zone.id});
    }
  }
  // Dijkstra over the visibility graph (legs checked lazily, each pair at most once).
  const std::size_t n = nodes.size();
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<std::size_t> parent(n, n);
  std::vector<bool> done(n, false);
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  dist[0] = 0.0;
  open.emplace(0.0, 0);
  while (!open.empty()) {
    const auto [d, u] = open.top();
    open.pop();
    if (done[u]) continue;
    done[u] = true;
    if (u == 1) break;
    for (std::size_t v = 0; v < n; ++v) {
      if (done[v]) continue;
      const double w = (nodes[v].p - nodes[u].p).norm();
      if (d + w >= dist[v]) continue;
      if (!gate.check_leg(nodes[u].p, nodes[v].p, "leg").empty()) continue;
      dist[v] = d + w;
      parent[v] = u;
      open.emplace(dist[v], v);
    }
  }
  if (!done[1]) {
    *why = "no route from " + format_point(first) + " to " + format_point(goal) +
           " clears the no-fly zones and the geofence";
    return std::nullopt;
  }
  std::vector<std::size_t> chain;
  for (std::size_t v = 1; v != 0; v = parent[v]) chain.push_back(v);
  std::reverse(chain.begin(), chain.end());
  PlannedPath out;
  out.waypoints = prefix;
  for (const auto v : chain) {
    out.waypoints.push_back(nodes[v].p);
    const auto& zone = nodes[v].zone;
    if (!zone.empty() && std::find(out.avoided.begin(), out.avoided.end(), zone) == out.avoided.end()) {
      out.avoided.push_back(zone);
    }
  }
  if (auto problem = gate.check_path(start, out.waypoints); !problem.empty()) {
    *why = "the planned route does not pass the gate: " + problem;
    return std::nullopt;
  }
  Eigen::Vector3d from = start;
  for (const auto& p : out.waypoints) {
    out.length_m += (p - from).norm();
    from = p;
  }
  return out;
}

}  // namespace a3::vehicle
