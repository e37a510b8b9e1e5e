// A flight's start → dynamics configuration.
#include "dynamics/scenario_setup.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dynamics/quadrotor_model.hpp"
#include "dynamics/wind_field.hpp"

namespace a3::dynamics {

void apply_flight_start(const FlightStart& start, bool start_on_ground, DynamicsNodeConfig& config) {
  if (!std::isfinite(start.wind_mps) || start.wind_mps < 0.0 || !std::isfinite(start.wind_dir_deg)) {
    throw std::invalid_argument("flight start: wind must be finite and >= 0, got " + std::to_string(start.wind_mps) +
                                " m/s from " + std::to_string(start.wind_dir_deg) + " deg");
  }
  if (!(start.battery_pct > 0.0 && start.battery_pct <= 100.0)) {
    throw std::invalid_argument("flight start: battery_pct must be in (0, 100], got " + std::to_string(start.battery_pct));
  }
  config.mean_wind_W_mps = wind_from_report(start.wind_mps, start.wind_dir_deg);
  config.params = with_payloads(config.params, start.payloads);
  const double z = start.p_W_m.z();
  VehicleState s;
  s.p_W_m = {start.p_W_m.x(), start.p_W_m.y(), start_on_ground ? 0.0 : z};
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(start.yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  const QuadrotorModel model(config.params);
  s.energy_used_J = (1.0 - start.battery_pct / 100.0) * model.battery_energy_J();
  if (!start_on_ground && z > 0.0) s.rotor_speed_radps.fill(model.hover_speed_radps());
  if (!start_on_ground) config.turbulence.reference_altitude_m = std::max(z, 3.0);
  config.initial_state = s;
}

}  // namespace a3::dynamics
