// What the vehicle can make good over the ground in wind. The flight controller flies a
// ground velocity toward its target, capped at the commanded speed and its horizontal speed
// limit; the thrust it may tilt into horizontal force is capped by its horizontal acceleration
// limit and its maximum tilt (bridge/fc/position_control.cpp). In steady flight that force
// balances the airframe's drag at the air-relative velocity (dynamics: F = c v + ½ρ CdA |v| v),
// so the air speed is at most the one whose drag equals it. Along a course u with wind w, the
// ground velocity is s·u (the crosswind is flown out), the air velocity s·u − w, and the
// largest s with |s·u − w| ≤ max air speed is u·w + sqrt(v_air,max² − |w⊥|²): the wind
// triangle. No s ≥ 0 works when the crosswind alone exceeds the air speed (the course cannot be
// held: 0 m/s). Vertical speeds are not affected.
#pragma once

#include <Eigen/Core>

#include <string>

namespace a3::vehicle {

// The fc's limits and the airframe's drag (the orchestrator copies them from the fc parameters
// and the airframe with its payloads; the defaults are the 3DR Iris with the default fc).
struct AirframeLimits {
  double mass_kg = 1.5;                    // with payloads (the fc's thrust setpoints assume it too)
  double linear_drag_Ns_per_m = 0.25;      // F = c v_air
  double drag_cdA_m2 = 0.05;               // F = ½ ρ CdA v_air²
  double air_density_kgpm3 = 1.225;
  double max_tilt_deg = 30.0;
  double max_horizontal_accel_mps2 = 4.0;
  double max_horizontal_speed_mps = 12.0;

  // Drag at an air speed, N.
  double drag_N(double airspeed_mps) const;
  // The largest horizontal force the fc commands in level flight: mass · min(a_max, g tan tilt).
  double max_horizontal_force_N() const;
  // The air speed whose drag is drag_N (the inverse of drag_N, for drag_N ≥ 0).
  double airspeed_for_drag_mps(double drag_N) const;
  // The air speed the maximum horizontal force can hold against drag.
  double max_airspeed_mps() const;

  // Throws std::invalid_argument naming the field ("airframe.mass_kg must be ... > 0, got 0").
  void validate(const std::string& where) const;
};

// The ground speed along a course for a commanded speed and a wind, from the limits.
class GroundSpeedModel {
 public:
  // Throws std::invalid_argument naming the bad field of limits.
  explicit GroundSpeedModel(AirframeLimits limits, Eigen::Vector2d wind_W_mps = Eigen::Vector2d::Zero());

  // The ground speed the vehicle makes good along course_W (any length > 0; a zero course
  // gives the commanded speed, capped), flying at commanded_mps. ≥ 0.
  double ground_speed_mps(const Eigen::Vector2d& course_W, double commanded_mps) const;
  // Time to fly the horizontal distance from a to b at commanded_mps (infinity when the
  // course cannot be made good).
  double horizontal_time_s(const Eigen::Vector2d& a_W_m, const Eigen::Vector2d& b_W_m, double commanded_mps) const;

  const AirframeLimits& limits() const { return limits_; }
  const Eigen::Vector2d& wind_W_mps() const { return wind_W_mps_; }
  void set_wind_W_mps(const Eigen::Vector2d& wind_W_mps) { wind_W_mps_ = wind_W_mps; }

 private:
  AirframeLimits limits_;
  double max_airspeed_mps_;
  Eigen::Vector2d wind_W_mps_;
};

}  // namespace a3::vehicle
