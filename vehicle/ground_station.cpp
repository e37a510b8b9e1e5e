// The simulated ground station.
#include "vehicle/ground_station.hpp"

#include <algorithm>
#include <cmath>

#include "vehicle/observation_json.hpp"

namespace a3::vehicle {
namespace {

PeerAnswer error(const std::string& status, const std::string& message) {
  PeerAnswer a;
  a.status = status;
  a.payload = {{"error", message}};
  return a;
}

// [x, y] or [x, y, z] of finite numbers; "" or what is wrong.
std::string read_point(const nlohmann::json& v, Eigen::Vector2d* xy, std::optional<double>* z) {
  if (!v.is_array() || v.size() < 2 || v.size() > 3) return "expected [x, y] or [x, y, z]";
  for (const auto& c : v) {
    if (!c.is_number() || !std::isfinite(c.get<double>())) return "expected finite numbers";
  }
  *xy = Eigen::Vector2d(v[0].get<double>(), v[1].get<double>());
  if (v.size() == 3) *z = v[2].get<double>();
  return "";
}

// A goal [x, y, z] below or above the route's altitude z: the route keeps its altitude and ends
// with the climb or descent to the goal's own z over the goal (a delivery's drop height), which
// must pass the gate too. "" or why not.
std::string end_at_goal_altitude(const SafetyGate& gate, const Eigen::Vector3d& start, const Eigen::Vector2d& goal_xy,
                                 double route_z_m, const std::optional<double>& goal_z_m, PlannedPath* plan) {
  if (!goal_z_m || std::abs(*goal_z_m - route_z_m) < 1e-9) return "";
  plan->waypoints.emplace_back(goal_xy.x(), goal_xy.y(), *goal_z_m);
  plan->length_m += std::abs(*goal_z_m - route_z_m);
  const std::string why = gate.check_path(start, plan->waypoints);
  return why.empty() ? "" : "the descent to the goal's altitude: " + why;
}

}  // namespace

GroundStation::GroundStation(const SafetyGate& gate, PlannerConfig config) : gate_(gate), config_(config) {
  config_.validate("planner");
}

PeerAnswer GroundStation::path_plan(const std::optional<Eigen::Vector3d>& position, const nlohmann::json& payload) const {
  if (!payload.contains("goal")) return error("error", "payload/goal: missing (expected [x, y] or [x, y, z])");
  Eigen::Vector2d goal_xy;
  std::optional<double> goal_z;
  if (auto why = read_point(payload["goal"], &goal_xy, &goal_z); !why.empty()) return error("error", "payload/goal: " + why);
  Eigen::Vector3d start;
  if (payload.contains("start")) {
    Eigen::Vector2d xy;
    std::optional<double> z;
    if (auto why = read_point(payload["start"], &xy, &z); !why.empty()) return error("error", "payload/start: " + why);
    start = Eigen::Vector3d(xy.x(), xy.y(), z.value_or(position ? position->z() : 0.0));
  } else if (position) {
    start = *position;
  } else {
    return error("failed", "payload/start: missing, and the vehicle's position is not known yet");
  }
  const Airspace& air = gate_.airspace();
  double z = 0.0;
  if (payload.contains("z")) {
    if (!payload["z"].is_number() || !std::isfinite(payload["z"].get<double>())) {
      return error("error", "payload/z: expected a finite number");
    }
    z = payload["z"].get<double>();
  } else if (goal_z) {
    z = *goal_z;
  } else if (start.z() >= air.min_altitude_m) {
    z = std::min(start.z(), air.max_altitude_m);
  } else {
    z = std::min(std::max(gate_.config().return_altitude_m, air.min_altitude_m), air.max_altitude_m);
  }
  std::string why;
  auto plan = plan_path(gate_, start, goal_xy, z, config_, &why);
  if (!plan) return error("failed", why);
  if (auto why_not = end_at_goal_altitude(gate_, start, goal_xy, z, goal_z, &*plan); !why_not.empty()) {
    return error("failed", why_not);
  }
  nlohmann::json waypoints = nlohmann::json::array();
  for (const auto& p : plan->waypoints) waypoints.push_back(point_array(p));
  const Eigen::Vector3d goal(goal_xy.x(), goal_xy.y(), goal_z.value_or(z));
  const double direct = (goal - start).norm();
  PeerAnswer a;
  a.payload = {{"waypoints", waypoints},
               {"z", rounded(z, 1)},
               {"length_m", rounded(plan->length_m, 1)},
               {"direct_m", rounded(direct, 1)},
               {"detour_m", rounded(std::max(plan->length_m - direct, 0.0), 1)},
               {"avoids", plan->avoided},
               {"gate", "passed"}};
  return a;
}

PeerAnswer GroundStation::handover_data(ImageStore& images, const nlohmann::json& payload) const {
  std::vector<std::string> ids;
  if (payload.contains("items")) {
    const auto& items = payload["items"];
    if (!items.is_array()) return error("error", "payload/items: expected an array");
    for (std::size_t i = 0; i < items.size(); ++i) {
      const auto& it = items[i];
      if (it.is_string()) {
        ids.push_back(it.get<std::string>());
      } else if (it.is_object() && it.contains("id") && it["id"].is_string()) {
        ids.push_back(it["id"].get<std::string>());
      } else if (it.is_object() && it.contains("image_id") && it["image_id"].is_string()) {
        ids.push_back(it["image_id"].get<std::string>());
      } else {
        return error("error", "payload/items/" + std::to_string(i) + ": expected an image id or {\"id\": ...}");
      }
    }
  }
  if (ids.empty()) {
    for (const auto& r : images.records()) {
      if (!r.downlinked) ids.push_back(r.id);
    }
  }
  PeerAnswer a;
  nlohmann::json received = nlohmann::json::array(), unknown = nlohmann::json::array();
  int64_t bytes = 0;
  for (const auto& id : ids) {
    ImageRecord* r = images.find(id);
    if (r == nullptr) {
      unknown.push_back(id);
      continue;
    }
    if (!r->downlinked) {
      bytes += r->size_bytes;
      r->downlinked = true;
    }
    received.push_back(id);
  }
  a.extra_bytes = bytes;
  a.payload = {{"received", received.size()}, {"items", received}, {"bytes", bytes}, {"unknown", unknown}};
  return a;
}

}  // namespace a3::vehicle
