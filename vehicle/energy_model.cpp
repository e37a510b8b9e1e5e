// Battery cost estimates for the safety gate.
#include "vehicle/energy_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/config_checks.hpp"

namespace a3::vehicle {
namespace {

void require_positive(double value, const std::string& where, const char* field) {
  common::require_positive(value, where + "." + field);
}

}  // namespace

double EnergyModel::percent_per_s() const { return hover_power_w / (battery_capacity_wh * 3600.0) * 100.0; }

double EnergyModel::percent_per_m(double speed_mps) const {
  return percent_per_s() * cruise_power_factor / speed_mps;
}

double EnergyModel::horizontal_time_s(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double speed_mps) const {
  if (ground_speed) return ground_speed->horizontal_time_s(a.head<2>(), b.head<2>(), speed_mps);
  return (b.head<2>() - a.head<2>()).norm() / speed_mps;
}

double EnergyModel::vertical_time_s(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  const double dz_m = b.z() - a.z();
  return dz_m > 0.0 ? dz_m / climb_speed_mps : -dz_m / descent_speed_mps;
}

double EnergyModel::leg_time_s(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double speed_mps) const {
  return horizontal_time_s(a, b, speed_mps) + vertical_time_s(a, b);
}

double EnergyModel::flown_leg_time_s(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double speed_mps) const {
  return std::max(horizontal_time_s(a, b, speed_mps), vertical_time_s(a, b));
}

double EnergyModel::leg_percent(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double speed_mps) const {
  const double vertical_s = vertical_time_s(a, b);
  const double horizontal_s = horizontal_time_s(a, b, speed_mps);
  return margin_factor * percent_per_s() * (cruise_power_factor * horizontal_s + vertical_s);
}

double EnergyModel::route_time_s(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& waypoints,
                                 double speed_mps) const {
  double t_s = 0.0;
  Eigen::Vector3d from = start;
  for (const auto& p : waypoints) {
    t_s += leg_time_s(from, p, speed_mps) + settle_s_per_waypoint;
    from = p;
  }
  return t_s;
}

double EnergyModel::route_percent(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& waypoints,
                                  double speed_mps) const {
  double percent = 0.0;
  Eigen::Vector3d from = start;
  for (const auto& p : waypoints) {
    percent += leg_percent(from, p, speed_mps) + margin_factor * settle_s_per_waypoint * percent_per_s();
    from = p;
  }
  return percent;
}

void EnergyModel::validate(const std::string& where) const {
  require_positive(hover_power_w, where, "hover_power_w");
  require_positive(cruise_power_factor, where, "cruise_power_factor");
  require_positive(battery_capacity_wh, where, "battery_capacity_wh");
  require_positive(cruise_speed_mps, where, "cruise_speed_mps");
  require_positive(climb_speed_mps, where, "climb_speed_mps");
  require_positive(descent_speed_mps, where, "descent_speed_mps");
  require_positive(margin_factor, where, "margin_factor");
  if (!std::isfinite(settle_s_per_waypoint) || settle_s_per_waypoint < 0.0) {
    throw std::invalid_argument(where + ".settle_s_per_waypoint must be a finite number >= 0, got " +
                                std::to_string(settle_s_per_waypoint));
  }
}

std::vector<Eigen::Vector3d> return_home_legs(const Eigen::Vector3d& p, const Eigen::Vector3d& home,
                                              double return_altitude_m, double min_altitude_m,
                                              double max_altitude_m) {
  const double cruise_z = std::min(std::max({p.z(), return_altitude_m, min_altitude_m}), max_altitude_m);
  return {Eigen::Vector3d(p.x(), p.y(), cruise_z), Eigen::Vector3d(home.x(), home.y(), cruise_z), home};
}

}  // namespace a3::vehicle
