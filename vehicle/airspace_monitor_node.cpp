// Safety measured on the true trajectory.
#include "vehicle/airspace_monitor_node.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "common/channels.hpp"
#include "common/config_checks.hpp"
#include "common/log.hpp"
#include "common/text_format.hpp"

namespace a3::vehicle {
namespace {

using common::formatted;

void require_non_negative(double value, const std::string& name) {
  common::require_non_negative(value, "AirspaceMonitorConfig." + name);
}

}  // namespace

void AirspaceMonitorConfig::validate() const {
  require_non_negative(default_min_separation_m, "default_min_separation_m");
  require_non_negative(takeoff_radius_m, "takeoff_radius_m");
  require_non_negative(vertical_transit_speed_mps, "vertical_transit_speed_mps");
  require_non_negative(vertical_transit_max_horizontal_mps, "vertical_transit_max_horizontal_mps");
  require_non_negative(airborne_altitude_m, "airborne_altitude_m");
  require_non_negative(hysteresis_m, "hysteresis_m");
  if (!std::isfinite(traffic_timeout_s) || traffic_timeout_s <= 0.0) {
    throw std::invalid_argument("AirspaceMonitorConfig.traffic_timeout_s must be > 0, got " +
                                std::to_string(traffic_timeout_s));
  }
  if (source.empty()) throw std::invalid_argument("AirspaceMonitorConfig.source must not be empty");
  if (airspace.min_altitude_m > airspace.max_altitude_m) {
    throw std::invalid_argument("AirspaceMonitorConfig.airspace: min_altitude_m is above max_altitude_m");
  }
}

AirspaceMonitorNode::AirspaceMonitorNode(AirspaceMonitorConfig config) : config_(std::move(config)) {
  config_.validate();
  zones_.resize(config_.airspace.no_fly_zones.size());
}

void AirspaceMonitorNode::start(common::Executor&, common::Bus& bus) {
  bus_ = &bus;
  bus.subscribe<a3lcm::vehicle_state_t>(common::channels::kState.of(config_.vehicle),
                                        [this](const a3lcm::vehicle_state_t& s, int64_t) { on_state(s); });
  bus.subscribe<a3lcm::traffic_state_t>(common::channels::kTraffic,
                                        [this](const a3lcm::traffic_state_t& t, int64_t) { on_traffic(t); });
}

std::vector<a3lcm::safety_event_t> AirspaceMonitorNode::events() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return events_;
}

std::map<std::string, double> AirspaceMonitorNode::closest_approach_m() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return closest_m_;
}

void AirspaceMonitorNode::on_traffic(const a3lcm::traffic_state_t& t) {
  auto it = peers_.find(t.id);
  if (it == peers_.end()) {
    Peer peer;
    peer.min_separation_m = config_.default_min_separation_m;
    for (const auto& plan : config_.airspace.traffic) {
      if (plan.id == t.id) peer.min_separation_m = plan.min_separation_m;
    }
    it = peers_.emplace(t.id, peer).first;
  }
  it->second.last = t;
}

void AirspaceMonitorNode::publish(const a3lcm::vehicle_state_t& s, const std::string& kind, double value,
                                  const std::string& detail) {
  a3lcm::safety_event_t e{};
  e.utime_us = s.utime_us;
  e.kind = kind;
  e.source = config_.source;
  for (int k = 0; k < 3; ++k) e.p_W_m[k] = s.p_W_m[k];
  e.value = value;
  e.detail = detail;
  common::log_info("airspace_monitor", kind + " " + detail);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    events_.push_back(e);
  }
  bus_->publish(common::channels::kSafety.of(config_.vehicle), e);
}

template <typename WhatFn>
void AirspaceMonitorNode::track(const a3lcm::vehicle_state_t& s, Violation& v, bool violating, bool cleared,
                                std::string_view kind, double value, bool higher_is_worse, const WhatFn& what) {
  if (!v.active) {
    if (!violating) return;
    v = {true, value, s.utime_us};
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (kind == "nfz_intrusion") ++counts_.nfz_intrusion;
      if (kind == "separation_breach") ++counts_.separation_breach;
      if (kind == "geofence_exit") ++counts_.geofence_exit;
      if (kind == "altitude_violation") ++counts_.altitude_violation;
    }
    publish(s, std::string(kind), value, "enter: " + what());
    return;
  }
  v.worst = higher_is_worse ? std::max(v.worst, value) : std::min(v.worst, value);
  if (!cleared) return;
  v.active = false;
  const double lasted_s = static_cast<double>(s.utime_us - v.since_us) * 1e-6;
  publish(s, std::string(kind), v.worst,
          "leave: " + what() + formatted(", lasted %.1f s", lasted_s) + formatted(", worst %.2f m", v.worst));
}

void AirspaceMonitorNode::on_state(const a3lcm::vehicle_state_t& s) {
  const Eigen::Vector3d p(s.p_W_m[0], s.p_W_m[1], s.p_W_m[2]);
  const Eigen::Vector3d v(s.v_W_mps[0], s.v_W_mps[1], s.v_W_mps[2]);
  if (!p.allFinite() || !v.allFinite()) {
    common::log_warn("airspace_monitor", "ignored a vehicle state with non-finite position or velocity");
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.states;
  }
  const Eigen::Vector2d xy = p.head<2>();
  airborne_ = !s.on_ground && p.z() > config_.airborne_altitude_m;
  if (!airborne_ || !have_takeoff_) {
    takeoff_xy_ = xy;
    have_takeoff_ = true;
  }
  check_zones_and_fence(s, p);
  check_altitude(s, p, v);
  check_separation(s, p);

  // Crash.
  if (s.crashed && !crashed_) {
    crashed_ = true;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counts_.crash;
    }
    publish(s, "crash", v.norm(), "enter: crashed" + formatted(" at %.2f m/s", v.norm()));
  }
}

void AirspaceMonitorNode::check_zones_and_fence(const a3lcm::vehicle_state_t& s, const Eigen::Vector3d& p) {
  const Airspace& air = config_.airspace;
  const Eigen::Vector2d xy = p.head<2>();
  const double h = config_.hysteresis_m;
  for (std::size_t i = 0; i < air.no_fly_zones.size(); ++i) {
    const NoFlyZone& z = air.no_fly_zones[i];
    const bool inside = z.contains(p);
    const double clearance = z.clearance_m(xy);
    const bool cleared = !inside && (clearance >= h || p.z() < z.floor_m - h || p.z() > z.ceiling_m + h);
    track(s, zones_[i], inside, cleared, "nfz_intrusion", std::max(-clearance, 0.0), true,
          [&] { return "no-fly zone " + z.id + formatted(" (%.2f m inside)", std::max(-clearance, 0.0)); });
  }
  if (air.geofence.size() >= 3) {
    const double clearance = air.geofence_clearance_m(xy);
    track(s, fence_, !air.inside_geofence(xy), clearance >= h, "geofence_exit", std::max(-clearance, 0.0), true,
          [&] { return "geofence" + formatted(" (%.2f m outside)", std::max(-clearance, 0.0)); });
  }
}

void AirspaceMonitorNode::check_altitude(const a3lcm::vehicle_state_t& s, const Eigen::Vector3d& p,
                                         const Eigen::Vector3d& v) {
  const Airspace& air = config_.airspace;
  const Eigen::Vector2d xy = p.head<2>();
  const double h = config_.hysteresis_m;
  track(s, high_, p.z() > air.max_altitude_m, p.z() <= air.max_altitude_m - h, "altitude_violation", p.z(), true,
        [&] { return "above the maximum " + formatted("%.1f m", air.max_altitude_m) + formatted(" at %.2f m", p.z()); });
  const double from_takeoff_m = (xy - takeoff_xy_).norm();
  const bool vertical_transit = std::abs(v.z()) >= config_.vertical_transit_speed_mps &&
                                v.head<2>().norm() <= config_.vertical_transit_max_horizontal_mps;
  const bool exempt = !airborne_ || from_takeoff_m <= config_.takeoff_radius_m || vertical_transit;
  track(s, low_, !exempt && p.z() < air.min_altitude_m, exempt || p.z() >= air.min_altitude_m + h,
        "altitude_violation", p.z(), false,
        [&] {
          return "below the minimum " + formatted("%.1f m", air.min_altitude_m) + formatted(" at %.2f m", p.z()) +
                 formatted(", %.1f m from the take-off point", from_takeoff_m);
        });
}

void AirspaceMonitorNode::check_separation(const a3lcm::vehicle_state_t& s, const Eigen::Vector3d& p) {
  const double h = config_.hysteresis_m;
  for (auto& entry : peers_) {
    const std::string& id = entry.first;  // named, not a structured binding: lambdas below take it
    auto& peer = entry.second;
    const double age_s = static_cast<double>(s.utime_us - peer.last.utime_us) * 1e-6;
    if (age_s > config_.traffic_timeout_s) {
      track(s, peer.breach, false, true, "separation_breach", peer.breach.worst, false,
            [&] { return "peer " + id + " (no longer reported)"; });
      continue;
    }
    const double dt = std::max(age_s, 0.0);
    const Eigen::Vector3d q(peer.last.p_W_m[0] + peer.last.v_W_mps[0] * dt, peer.last.p_W_m[1] + peer.last.v_W_mps[1] * dt,
                            peer.last.p_W_m[2] + peer.last.v_W_mps[2] * dt);
    const double d = (p - q).norm();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto [it, fresh] = closest_m_.emplace(id, d);
      if (!fresh) it->second = std::min(it->second, d);
    }
    track(s, peer.breach, d < peer.min_separation_m, d > peer.min_separation_m + h, "separation_breach", d, false,
          [&] { return "peer " + id + formatted(" at %.2f m", d) + formatted(", minimum %.1f m", peer.min_separation_m); });
  }
}

}  // namespace a3::vehicle
