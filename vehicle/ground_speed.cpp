// The wind triangle with the fc's limits and the airframe's drag.
#include "vehicle/ground_speed.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/config_checks.hpp"

namespace a3::vehicle {
namespace {

constexpr double kGravity_mps2 = 9.80665;

void require_positive(double value, const std::string& where, const char* field) {
  common::require_positive(value, where + "." + field);
}

void require_non_negative(double value, const std::string& where, const char* field) {
  common::require_non_negative(value, where + "." + field);
}

}  // namespace

double AirframeLimits::drag_N(double airspeed_mps) const {
  return linear_drag_Ns_per_m * airspeed_mps + 0.5 * air_density_kgpm3 * drag_cdA_m2 * airspeed_mps * airspeed_mps;
}

double AirframeLimits::max_horizontal_force_N() const {
  return mass_kg * std::min(max_horizontal_accel_mps2, kGravity_mps2 * std::tan(max_tilt_deg * M_PI / 180.0));
}

double AirframeLimits::airspeed_for_drag_mps(double drag) const {
  const double quadratic = 0.5 * air_density_kgpm3 * drag_cdA_m2;
  const double force = std::max(drag, 0.0);
  if (quadratic <= 0.0) return force / linear_drag_Ns_per_m;
  // quadratic v² + linear v − force = 0, the positive root (written to stay exact for small c).
  return 2.0 * force /
         (linear_drag_Ns_per_m + std::sqrt(linear_drag_Ns_per_m * linear_drag_Ns_per_m + 4.0 * quadratic * force));
}

double AirframeLimits::max_airspeed_mps() const { return airspeed_for_drag_mps(max_horizontal_force_N()); }

void AirframeLimits::validate(const std::string& where) const {
  require_positive(mass_kg, where, "mass_kg");
  require_non_negative(linear_drag_Ns_per_m, where, "linear_drag_Ns_per_m");
  require_non_negative(drag_cdA_m2, where, "drag_cdA_m2");
  require_positive(air_density_kgpm3, where, "air_density_kgpm3");
  require_positive(max_horizontal_accel_mps2, where, "max_horizontal_accel_mps2");
  require_positive(max_horizontal_speed_mps, where, "max_horizontal_speed_mps");
  if (!std::isfinite(max_tilt_deg) || max_tilt_deg <= 0.0 || max_tilt_deg >= 90.0) {
    throw std::invalid_argument(where + ".max_tilt_deg must be in (0, 90), got " + std::to_string(max_tilt_deg));
  }
  if (linear_drag_Ns_per_m <= 0.0 && drag_cdA_m2 <= 0.0) {
    throw std::invalid_argument(where + ": linear_drag_Ns_per_m and drag_cdA_m2 are both 0 (no drag: no speed limit)");
  }
}

GroundSpeedModel::GroundSpeedModel(AirframeLimits limits, Eigen::Vector2d wind_W_mps)
    : limits_(limits), max_airspeed_mps_(0.0), wind_W_mps_(std::move(wind_W_mps)) {
  limits_.validate("airframe");
  max_airspeed_mps_ = limits_.max_airspeed_mps();
}

double GroundSpeedModel::ground_speed_mps(const Eigen::Vector2d& course_W, double commanded_mps) const {
  const double wanted = std::clamp(commanded_mps, 0.0, limits_.max_horizontal_speed_mps);
  if (course_W.norm() < 1e-9) return wanted;
  const Eigen::Vector2d u = course_W.normalized();
  const double along_mps = u.dot(wind_W_mps_);
  const double cross_mps = (wind_W_mps_ - along_mps * u).norm();
  if (cross_mps >= max_airspeed_mps_) return 0.0;
  const double reachable = along_mps + std::sqrt(max_airspeed_mps_ * max_airspeed_mps_ - cross_mps * cross_mps);
  return std::clamp(reachable, 0.0, wanted);
}

double GroundSpeedModel::horizontal_time_s(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                           double commanded_mps) const {
  const double distance_m = (b - a).norm();
  if (distance_m < 1e-9) return 0.0;
  const double speed = ground_speed_mps(b - a, commanded_mps);
  return speed > 0.0 ? distance_m / speed : std::numeric_limits<double>::infinity();
}

}  // namespace a3::vehicle
