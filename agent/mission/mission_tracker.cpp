// Mission objectives from events.
#include "agent/mission/mission_tracker.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "agent/mission/objective_rules.hpp"

namespace a3::agent {
namespace {

Eigen::Vector2d xy(const double p[3]) { return {p[0], p[1]}; }

bool sensor_matches(const std::string& wanted, const std::string& got) {
  return wanted.empty() || wanted == "any" || wanted == got;
}

}  // namespace

MissionTracker::MissionTracker(Mission mission) : mission_(std::move(mission)), progress_(mission_.objectives.size()) {
  state_.p_W_m[0] = mission_.home_W_m.x();
  state_.p_W_m[1] = mission_.home_W_m.y();
  state_.p_W_m[2] = mission_.home_W_m.z();
  state_.on_ground = true;
}

void MissionTracker::mark(std::size_t i, double t_s, const std::string& detail) {
  if (progress_[i].done && progress_[i].detail == detail) return;
  if (!progress_[i].done) progress_[i].done_at_s = t_s;
  progress_[i].done = true;
  progress_[i].detail = detail;
  ++version_;
}

void MissionTracker::on_state(const a3lcm::vehicle_state_t& s) {
  const double t_s = s.utime_us * 1e-6;
  const double dt = last_state_t_s_ < 0.0 ? 0.0 : t_s - last_state_t_s_;
  last_state_t_s_ = t_s;
  state_ = s;
  have_state_ = true;
  const bool thermal_on = std::find(active_sensors_.begin(), active_sensors_.end(), "thermal") != active_sensors_.end();
  for (std::size_t i = 0; i < mission_.objectives.size(); ++i) {
    const Objective& o = mission_.objectives[i];
    if (o.type == ObjectiveType::kThermalSearch && !progress_[i].done && thermal_on &&
        (xy(s.p_W_m) - o.hidden_target).norm() <= o.radius_m && s.p_W_m[2] <= o.altitude_m + kThermalSightAbove_m &&
        !s.on_ground) {
      mark(i, t_s, "target seen by the thermal camera");
    }
    if (o.type == ObjectiveType::kDelivery && !progress_[i].done) track_delivery(i, s, dt);
  }
  update_landing();
}

void MissionTracker::track_delivery(std::size_t i, const a3lcm::vehicle_state_t& s, double dt_s) {
  const Objective& o = mission_.objectives[i];
  ObjectiveProgress& p = progress_[i];
  const double distance_m = (xy(s.p_W_m) - o.point).norm();
  const bool in_radius = distance_m <= o.radius_m;
  if (in_radius) p.lowest_in_radius_m = std::min(p.lowest_in_radius_m, s.p_W_m[2]);
  p.dwell_s = in_radius && s.p_W_m[2] <= drop_ceiling_m(o) ? p.dwell_s + dt_s : 0.0;
  p.longest_dwell_s = std::max(p.longest_dwell_s, p.dwell_s);
  if (p.dwell_s >= kDropDwell_s) {
    char text[120];
    std::snprintf(text, sizeof text, "delivered at the drop point (%.1f m from it, %.1f m altitude)", distance_m,
                  s.p_W_m[2]);
    mark(i, s.utime_us * 1e-6, text);
  }
}

std::string MissionTracker::why_not_done(std::size_t i) const {
  const Objective& o = mission_.objectives[i];
  const ObjectiveProgress& p = progress_[i];
  if (p.done || o.type != ObjectiveType::kDelivery || p.lowest_in_radius_m == kNever) return "";
  char text[240];
  if (p.lowest_in_radius_m > drop_ceiling_m(o)) {
    std::snprintf(text, sizeof text,
                  "not delivered: the lowest altitude within %g m of the drop point was %.1f m; a drop needs %g m or "
                  "lower held for %g s",
                  o.radius_m, p.lowest_in_radius_m, drop_ceiling_m(o), kDropDwell_s);
  } else {
    std::snprintf(text, sizeof text,
                  "not delivered: held at or below %g m within %g m of the drop point for %.1f s at most; a drop needs "
                  "%g s without a break",
                  drop_ceiling_m(o), o.radius_m, p.longest_dwell_s, kDropDwell_s);
  }
  return text;
}

void MissionTracker::on_fc_status(const a3lcm::fc_status_t& s) {
  fc_ = s;
  update_landing();
}

void MissionTracker::update_landing() {
  for (std::size_t i = 0; i < mission_.objectives.size(); ++i) {
    const Objective& o = mission_.objectives[i];
    if (o.type != ObjectiveType::kReturnAndLand) continue;
    const double distance = (xy(state_.p_W_m) - mission_.home_W_m.head<2>()).norm();
    const bool landed = have_state_ && state_.on_ground && !state_.crashed && !fc_.armed;
    const bool ok = landed && distance <= o.radius_m;
    if (ok) {
      char text[80];
      std::snprintf(text, sizeof text, "landed %.1f m from home", distance);
      mark(i, state_.utime_us * 1e-6, text);
    } else if (progress_[i].done) {
      progress_[i].done = false;  // took off again
      progress_[i].detail.clear();
      ++version_;
    }
  }
}

void MissionTracker::on_payload(const a3lcm::payload_event_t& e) {
  if (e.kind == "activated") {
    if (std::find(active_sensors_.begin(), active_sensors_.end(), e.sensor) == active_sensors_.end()) {
      active_sensors_.push_back(e.sensor);
    }
    return;
  }
  if (e.kind == "deactivated") {
    active_sensors_.erase(std::remove(active_sensors_.begin(), active_sensors_.end(), e.sensor), active_sensors_.end());
    return;
  }
  if (e.kind != "capture") return;
  const double t_s = e.utime_us * 1e-6;
  const Eigen::Vector2d p = xy(e.p_W_m);
  for (std::size_t i = 0; i < mission_.objectives.size(); ++i) {
    const Objective& o = mission_.objectives[i];
    ObjectiveProgress& pr = progress_[i];
    if (pr.done || !sensor_matches(o.sensor, e.sensor)) continue;
    switch (o.type) {
      case ObjectiveType::kSurvey:
        // A lawnmower's line ends lie on the area's edge: captures within 10 m of it count.
        if (common::polygon_contains(o.area, p) || common::polygon_edge_distance(o.area, p) <= kSurveyEdgeMargin_m) {
          ++pr.count;
          ++version_;
          if (pr.count >= o.images_required) {
            mark(i, t_s, std::to_string(pr.count) + " images of the area");
          }
        }
        break;
      case ObjectiveType::kImagePoint:
        if ((p - o.point).norm() <= o.radius_m) mark(i, t_s, "imaged by " + e.sensor + " (" + e.item_id + ")");
        break;
      case ObjectiveType::kThermalSearch:
        if ((p - o.hidden_target).norm() <= o.radius_m) mark(i, t_s, "target found in " + e.item_id);
        break;
      default:
        break;
    }
  }
}

bool MissionTracker::all_done() const {
  for (const auto& p : progress_) {
    if (!p.done) return false;
  }
  return true;
}

nlohmann::json MissionTracker::to_json() const {
  nlohmann::json objectives = nlohmann::json::array();
  for (std::size_t i = 0; i < mission_.objectives.size(); ++i) {
    const Objective& o = mission_.objectives[i];
    const ObjectiveProgress& p = progress_[i];
    nlohmann::json j = {{"id", o.id}, {"type", to_string(o.type)}, {"done", p.done}, {"detail", p.detail}};
    if (p.done) j["done_at_s"] = p.done_at_s;
    if (const std::string why = why_not_done(i); !why.empty()) j["why_not"] = why;
    if (o.type == ObjectiveType::kSurvey) j["images"] = p.count;
    objectives.push_back(j);
  }
  return {{"objectives", objectives},
          {"all_done", all_done()},
          {"mode", fc_.mode},
          {"armed", fc_.armed},
          {"on_ground", state_.on_ground},
          {"position", {state_.p_W_m[0], state_.p_W_m[1], state_.p_W_m[2]}}};
}

}  // namespace a3::agent
