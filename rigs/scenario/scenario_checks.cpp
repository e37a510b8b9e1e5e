// Scenario semantic rules.
#include "rigs/scenario/scenario_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/polygon.hpp"
#include "dynamics/quadrotor_model.hpp"

namespace a3::rigs {
namespace {

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

std::string zone_name(const Scenario& s, std::size_t i) {
  return "no-fly zone '" + s.airspace.no_fly_zones[i].id + "' (/airspace/no_fly_zones/" + std::to_string(i) + ")";
}

bool zone_covers_altitude(const agent::NoFlyZone& z, double low_m, double high_m) {
  return z.floor_m <= high_m && z.ceiling_m >= low_m;
}

bool zone_overlaps_area(const agent::NoFlyZone& z, const common::Polygon2d& area) {
  for (const auto& p : area) {
    if (z.clearance_m(p) <= 0.0) return true;
  }
  if (z.polygon.empty()) {
    return common::polygon_contains(area, z.centre) || common::polygon_edge_distance(area, z.centre) < z.radius_m;
  }
  for (const auto& p : z.polygon) {
    if (common::polygon_contains(area, p)) return true;
  }
  for (std::size_t i = 0; i < area.size(); ++i) {
    if (common::segment_enters_polygon(z.polygon, area[i], area[(i + 1) % area.size()])) return true;
  }
  return false;
}

void check_home(const Scenario& s, const std::string& where, std::vector<std::string>& out) {
  const Eigen::Vector2d home = s.mission.home_W_m.head<2>();
  const std::string w = where + ": /initial_state/uav/pose: home " + format("(%g, %g)", home.x(), home.y());
  if (!s.airspace.inside_geofence(home)) out.push_back(w + " lies outside the geofence (/initial_state/airspace/geofence)");
  // The vehicle climbs from the ground to the cruise altitude above home.
  for (std::size_t i = 0; i < s.airspace.no_fly_zones.size(); ++i) {
    const auto& z = s.airspace.no_fly_zones[i];
    if (z.clearance_m(home) <= 0.0 && zone_covers_altitude(z, 0.0, s.mission.cruise_altitude_m)) {
      out.push_back(w + " lies inside " + zone_name(s, i) + " below the cruise altitude");
    }
  }
}

// The altitudes an objective is flown at: its own, and down to the drop for a delivery.
std::pair<double, double> objective_altitudes(const agent::Objective& o) {
  if (o.type == agent::ObjectiveType::kDelivery) return {std::min(o.drop_altitude_m, o.altitude_m), o.altitude_m};
  return {o.altitude_m, o.altitude_m};
}

void check_objective_place(const Scenario& s, std::size_t index, const std::string& where, std::vector<std::string>& out) {
  const agent::Objective& o = s.mission.objectives[index];
  if (o.type == agent::ObjectiveType::kReturnAndLand) return;
  const std::string w = where + ": /mission/objectives/" + std::to_string(index);
  const bool has_area = !o.area.empty();
  const std::string field = has_area ? "/area" : "/point";
  const common::Polygon2d points = has_area ? o.area : common::Polygon2d{o.point};
  for (const auto& p : points) {
    if (!s.airspace.inside_geofence(p)) {
      out.push_back(w + field + ": " + format("(%g, %g)", p.x(), p.y()) + " lies outside the geofence");
      break;
    }
  }
  const auto [low_m, high_m] = objective_altitudes(o);
  for (std::size_t i = 0; i < s.airspace.no_fly_zones.size(); ++i) {
    const auto& z = s.airspace.no_fly_zones[i];
    if (!zone_covers_altitude(z, low_m, high_m)) continue;
    const bool inside = has_area ? zone_overlaps_area(z, o.area) : z.clearance_m(o.point) <= 0.0;
    if (inside) out.push_back(w + field + ": " + (has_area ? "overlaps " : "lies inside ") + zone_name(s, i) +
                              format(" at %g m", high_m));
  }
  if (!s.airspace.altitude_ok(o.altitude_m)) {
    out.push_back(w + "/altitude_m: " + format("%g m is outside the altitude envelope [%g, %g] m", o.altitude_m,
                                               s.airspace.min_altitude_m, s.airspace.max_altitude_m));
  }
}

void check_mission(const Scenario& s, const std::string& where, std::vector<std::string>& out) {
  const auto& m = s.mission;
  if (!s.airspace.altitude_ok(m.cruise_altitude_m)) {
    out.push_back(where + ": /mission/cruise_altitude_m: " +
                  format("%g m is outside the altitude envelope [%g, %g] m (airspace and policy alt_bounds)",
                         m.cruise_altitude_m, s.airspace.min_altitude_m, s.airspace.max_altitude_m));
  }
  if (!(m.time_limit_s > 0.0)) out.push_back(where + ": /mission/time_limit_s: must be > 0");
  if (!(m.cruise_speed_mps > 0.0)) out.push_back(where + ": /mission/cruise_speed_mps: must be > 0");
  for (std::size_t i = 0; i < m.objectives.size(); ++i) check_objective_place(s, i, where, out);
}

void check_airframe(const Scenario& s, const dynamics::VehicleParams& loaded, double max_tilt_deg,
                    const std::string& where, std::vector<std::string>& out) {
  const dynamics::QuadrotorModel model(loaded);
  if (model.hover_throttle() > kMaxHoverThrottle) {
    out.push_back(where + ": /initial_state/uav/payloads: " +
                  format("%g kg of payload needs hover throttle %.2f on airframe '", loaded.payload_mass_kg,
                         model.hover_throttle()) + s.airframe + "'" +
                  format(" (at most %.2f, the rest is the control margin)", kMaxHoverThrottle) +
                  (s.airframe == "heavy-lift" ? "; no built-in airframe can: lighten the payload"
                                              : "; use \"airframe\": \"heavy-lift\" or lighten the payload"));
    return;  // without lift the wind limit means nothing
  }
  const double limit_mps = wind_hold_limit_mps(loaded, max_tilt_deg);
  const auto& env = s.start.env;
  if (env.wind_mps > kWindMargin * limit_mps) {
    out.push_back(where + ": /initial_state/env/wind_mps: " +
                  format("%g m/s is more than %.1f m/s (%.0f %%", env.wind_mps, kWindMargin * limit_mps, kWindMargin * 100.0) +
                  format(" of the %.1f m/s airframe '", limit_mps) + s.airframe +
                  format("' can hold position against at its %g deg tilt limit)", max_tilt_deg));
  }
  if (env.gust_mps && *env.gust_mps > limit_mps) {
    out.push_back(where + ": /initial_state/env/gust_mps: " +
                  format("%g m/s is more than the %.1f m/s airframe '", *env.gust_mps, limit_mps) + s.airframe +
                  "' can hold against");
  }
}

}  // namespace

double wind_hold_limit_mps(const dynamics::VehicleParams& v, double max_tilt_deg) {
  const double weight_N = v.total_mass_kg() * dynamics::kGravity_mps2;
  const double max_thrust_N = 4.0 * v.rotor.thrust_coeff_N_per_radps2 * v.rotor.max_speed_radps * v.rotor.max_speed_radps;
  const double thrust_tilt_rad = weight_N < max_thrust_N ? std::acos(weight_N / max_thrust_N) : 0.0;
  const double tilt_rad = std::min(max_tilt_deg * M_PI / 180.0, thrust_tilt_rad);
  return dynamics::airspeed_for_drag_mps(v.aero, weight_N * std::tan(tilt_rad));
}

std::vector<std::string> scenario_problems(const Scenario& s, const dynamics::VehicleParams& loaded_airframe,
                                           double max_tilt_deg, const std::string& where) {
  std::vector<std::string> out;
  check_home(s, where, out);
  check_mission(s, where, out);
  check_airframe(s, loaded_airframe, max_tilt_deg, where, out);
  return out;
}

}  // namespace a3::rigs
