// The safety gate's rules.
#include "vehicle/safety_gate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "common/text_format.hpp"

namespace a3::vehicle {
namespace {

using common::formatted;

std::string m(double value) { return formatted("%.1f m", value); }
std::string pct(double value) { return formatted("%.1f %%", value); }

void require_non_negative(double value, const std::string& where, const char* field) {
  if (!std::isfinite(value) || value < 0.0) {
    throw std::invalid_argument(where + "." + field + " must be a finite number >= 0, got " + std::to_string(value));
  }
}

bool within_vertical(const NoFlyZone& z, double altitude_m) { return altitude_m >= z.floor_m && altitude_m <= z.ceiling_m; }

// A leg that starts inside a zone's margin passes when it only moves away from the zone: its
// end is clear of the margin and its clearance never shrinks along the way (sampled every 0.5 m).
bool moves_away(const NoFlyZone& z, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double margin_m) {
  const bool end_clear = !within_vertical(z, b.z()) || z.clearance_m(b.head<2>()) >= margin_m;
  if (!end_clear) return false;
  const double start_clearance = z.clearance_m(a.head<2>());
  const double length = (b - a).norm();
  const int samples = std::clamp(static_cast<int>(std::ceil(length / 0.5)), 1, 4000);
  for (int i = 1; i <= samples; ++i) {
    const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / samples);
    if (within_vertical(z, p.z()) && z.clearance_m(p.head<2>()) < std::min(start_clearance, margin_m) - 1e-6) {
      return false;
    }
  }
  return true;
}

}  // namespace

std::string format_point(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.1f, %.1f, %.1f)", p.x(), p.y(), p.z());
  return text;
}

void GateConfig::validate(const std::string& where) const {
  require_non_negative(geofence_margin_m, where, "geofence_margin_m");
  require_non_negative(nfz_margin_m, where, "nfz_margin_m");
  require_non_negative(nfz_vertical_margin_m, where, "nfz_vertical_margin_m");
  require_non_negative(battery_reserve_pct, where, "battery_reserve_pct");
  require_non_negative(return_altitude_m, where, "return_altitude_m");
  if (battery_reserve_pct > 100.0) {
    throw std::invalid_argument(where + ".battery_reserve_pct must be <= 100, got " + std::to_string(battery_reserve_pct));
  }
  if (!std::isfinite(max_speed_mps) || max_speed_mps <= 0.0) {
    throw std::invalid_argument(where + ".max_speed_mps must be a finite number > 0, got " + std::to_string(max_speed_mps));
  }
}

SafetyGate::SafetyGate(Airspace airspace, GateConfig config, EnergyModel energy, Eigen::Vector3d home_W_m)
    : airspace_(std::move(airspace)), config_(config), energy_(energy), home_W_m_(std::move(home_W_m)) {}

NoFlyZone SafetyGate::widened(const NoFlyZone& zone) const {
  NoFlyZone out = zone;
  out.floor_m -= config_.nfz_vertical_margin_m;
  out.ceiling_m += config_.nfz_vertical_margin_m;
  return out;
}

std::string SafetyGate::check_target(const Eigen::Vector3d& p, const std::string& what) const {
  const std::string name = what + " " + format_point(p);
  if (!p.allFinite()) return what + " is not a finite point";
  if (p.z() > airspace_.max_altitude_m) {
    return name + ": altitude " + m(p.z()) + " is above the envelope's maximum " + m(airspace_.max_altitude_m);
  }
  if (p.z() < airspace_.min_altitude_m) {
    return name + ": altitude " + m(p.z()) + " is below the envelope's minimum " + m(airspace_.min_altitude_m);
  }
  const Eigen::Vector2d xy = p.head<2>();
  if (!airspace_.inside_geofence(xy)) return name + " is outside the geofence";
  const double fence_clearance = airspace_.geofence_clearance_m(xy);
  if (fence_clearance < config_.geofence_margin_m) {
    return name + " is " + m(fence_clearance) + " from the geofence edge, closer than the " +
           m(config_.geofence_margin_m) + " margin";
  }
  for (const auto& zone : airspace_.no_fly_zones) {
    if (zone.contains(p)) return name + " is inside no-fly zone " + zone.id;
    const NoFlyZone z = widened(zone);
    if (!within_vertical(z, p.z())) continue;
    const double clearance = z.clearance_m(xy);
    if (clearance < config_.nfz_margin_m) {
      return name + " is " + m(std::max(clearance, 0.0)) + " from no-fly zone " + zone.id + ", closer than the " +
             m(config_.nfz_margin_m) + " margin";
    }
  }
  return "";
}

std::string SafetyGate::check_leg(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const std::string& what) const {
  const std::string name = what + " from " + format_point(a) + " to " + format_point(b);
  if (!a.allFinite() || !b.allFinite()) return what + " has a point that is not finite";
  const Eigen::Vector2d a2 = a.head<2>(), b2 = b.head<2>();
  if (airspace_.geofence.size() >= 3 && airspace_.inside_geofence(a2)) {
    const auto& fence = airspace_.geofence;
    for (std::size_t i = 0, j = fence.size() - 1; i < fence.size(); j = i++) {
      if (common::segments_intersect(a2, b2, fence[j], fence[i])) return name + " leaves the geofence";
    }
  }
  for (const auto& zone : airspace_.no_fly_zones) {
    const NoFlyZone z = widened(zone);
    if (!z.crossed_by(a, b, config_.nfz_margin_m)) continue;
    const bool starts_near = within_vertical(z, a.z()) && z.clearance_m(a2) < config_.nfz_margin_m;
    if (starts_near && moves_away(z, a, b, config_.nfz_margin_m)) continue;
    return name + " passes through or within " + m(config_.nfz_margin_m) + " of no-fly zone " + zone.id;
  }
  return "";
}

std::string SafetyGate::check_path(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& waypoints) const {
  const bool one = waypoints.size() == 1;
  Eigen::Vector3d from = start;
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const std::string index = std::to_string(i + 1);
    if (auto why = check_target(waypoints[i], one ? "target" : "waypoint " + index); !why.empty()) return why;
    if (auto why = check_leg(from, waypoints[i], one ? "path" : "leg " + index); !why.empty()) return why;
    from = waypoints[i];
  }
  return "";
}

BatteryEstimate SafetyGate::estimate_battery(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& waypoints,
                                             double speed_mps, double battery_pct) const {
  BatteryEstimate e;
  e.now_pct = battery_pct;
  e.route_pct = energy_.route_percent(start, waypoints, speed_mps);
  const Eigen::Vector3d end = waypoints.empty() ? start : waypoints.back();
  const auto legs = return_home_legs(end, home_W_m_, config_.return_altitude_m, airspace_.min_altitude_m,
                                     airspace_.max_altitude_m);
  Eigen::Vector3d from = end;
  for (const auto& p : legs) {
    e.return_pct += energy_.leg_percent(from, p, energy_.cruise_speed_mps);
    from = p;
  }
  e.left_pct = battery_pct - e.route_pct - e.return_pct;
  return e;
}

std::string SafetyGate::check_battery(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& waypoints,
                                      double speed_mps, double battery_pct) const {
  const BatteryEstimate e = estimate_battery(start, waypoints, speed_mps, battery_pct);
  if (e.left_pct >= config_.battery_reserve_pct) return "";
  return "battery reserve: " + pct(e.now_pct) + " now, the route needs about " + pct(e.route_pct) +
         " and the return home from its end " + pct(e.return_pct) + ", leaving " + pct(e.left_pct) +
         ", below the " + pct(config_.battery_reserve_pct) + " reserve";
}

std::string SafetyGate::check_speed(double speed_mps) const {
  if (speed_mps > config_.max_speed_mps) {
    return "speed " + formatted("%.1f m/s", speed_mps) + " is above the vehicle's maximum " +
           formatted("%.1f m/s", config_.max_speed_mps);
  }
  return "";
}

std::string SafetyGate::check_route(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& waypoints,
                                    double speed_mps, double battery_pct) const {
  if (auto why = check_speed(speed_mps); !why.empty()) return why;
  if (auto why = check_path(start, waypoints); !why.empty()) return why;
  return check_battery(start, waypoints, speed_mps, battery_pct);
}

std::string SafetyGate::check_descent(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d ground(p.x(), p.y(), 0.0);
  for (const auto& zone : airspace_.no_fly_zones) {
    if (zone.crossed_by(p, ground, 0.0)) {
      return "landing at " + format_point(p) + " descends through no-fly zone " + zone.id;
    }
  }
  return "";
}

}  // namespace a3::vehicle
