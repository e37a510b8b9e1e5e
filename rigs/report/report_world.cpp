// A scenario's world as plain JSON for the episode report.
#include "rigs/report/report_world.hpp"

#include <cmath>

namespace a3::rigs {
namespace {

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json points_json(const common::Polygon2d& points) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : points) out.push_back({p.x(), p.y()});
  return out;
}

nlohmann::json zone_json(const agent::NoFlyZone& z) {
  return {{"id", z.id},
          {"polygon", points_json(z.polygon)},
          {"centre", {z.centre.x(), z.centre.y()}},
          {"radius_m", z.radius_m},
          {"floor_m", finite_or_null(z.floor_m)},
          {"ceiling_m", finite_or_null(z.ceiling_m)}};
}

bool has_point(agent::ObjectiveType type) {
  return type == agent::ObjectiveType::kImagePoint || type == agent::ObjectiveType::kDelivery;
}

nlohmann::json objective_json(const agent::Objective& o, const Eigen::Vector3d& home_W_m) {
  nlohmann::json point = nullptr;
  if (has_point(o.type)) point = {o.point.x(), o.point.y()};
  if (o.type == agent::ObjectiveType::kReturnAndLand) point = {home_W_m.x(), home_W_m.y()};
  return {{"id", o.id}, {"type", agent::to_string(o.type)}, {"point", point}, {"radius_m", o.radius_m},
          {"area", points_json(o.area)}};
}

nlohmann::json peer_json(const agent::TrafficPlan& t) {
  nlohmann::json path = nlohmann::json::array();
  for (const auto& w : t.path) path.push_back({w.t_s, w.p_W_m.x(), w.p_W_m.y(), w.p_W_m.z()});
  return {{"id", t.id}, {"path", path}, {"min_separation_m", t.min_separation_m}};
}

}  // namespace

nlohmann::json report_world_json(const Scenario& s) {
  nlohmann::json zones = nlohmann::json::array(), objectives = nlohmann::json::array();
  nlohmann::json peers = nlohmann::json::array(), degradations = nlohmann::json::array();
  for (const auto& z : s.airspace.no_fly_zones) zones.push_back(zone_json(z));
  for (const auto& o : s.mission.objectives) objectives.push_back(objective_json(o, s.mission.home_W_m));
  for (const auto& t : s.airspace.traffic) peers.push_back(peer_json(t));
  for (const auto& w : s.network.degradations) degradations.push_back({w.start_s, w.duration_s});
  const AltitudeBounds envelope = s.start.envelope();
  return {{"geofence", points_json(s.airspace.geofence)},
          {"zones", zones},
          {"objectives", objectives},
          {"home", {s.mission.home_W_m.x(), s.mission.home_W_m.y()}},
          {"peers", peers},
          {"degradations", degradations},
          {"alt_bounds", {finite_or_null(envelope.min_m), finite_or_null(envelope.max_m)}}};
}

}  // namespace a3::rigs
