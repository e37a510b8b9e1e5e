// Attitude and rate control, mixing.
#include "bridge/fc/attitude_control.hpp"

#include <algorithm>
#include <cmath>

namespace a3::bridge {

AttitudeController::AttitudeController(const FcParams& params)
    : params_(params),
      inertia_kgm2_(params.vehicle.inertia_xx_kgm2, params.vehicle.inertia_yy_kgm2, params.vehicle.inertia_zz_kgm2) {}

Eigen::Vector3d AttitudeController::rate_setpoint(const Eigen::Quaterniond& q_WB,
                                                  const Eigen::Quaterniond& q_sp) const {
  Eigen::Quaterniond e = q_WB.conjugate() * q_sp;  // rotation still to do, body frame
  if (e.w() < 0.0) e.coeffs() = -e.coeffs();        // the short way round
  const Eigen::Vector3d axis_angle = 2.0 * e.vec();
  const FcGains& g = params_.gains;
  const FcLimits& l = params_.limits;
  Eigen::Vector3d w_sp(g.attitude_p * axis_angle.x(), g.attitude_p * axis_angle.y(), g.yaw_p * axis_angle.z());
  w_sp.x() = std::clamp(w_sp.x(), -l.max_rate_radps, l.max_rate_radps);
  w_sp.y() = std::clamp(w_sp.y(), -l.max_rate_radps, l.max_rate_radps);
  w_sp.z() = std::clamp(w_sp.z(), -l.max_yaw_rate_radps, l.max_yaw_rate_radps);
  return w_sp;
}

Eigen::Vector3d AttitudeController::torque(const Eigen::Vector3d& w_B, const Eigen::Vector3d& w_sp, double dt_s) {
  const Eigen::Vector3d error = w_sp - w_B;
  constexpr double kIntegralLimit = 0.5;  // rad/s·s
  if (dt_s > 0.0) {
    rate_integral_ = (rate_integral_ + error * dt_s).cwiseMax(-kIntegralLimit).cwiseMin(kIntegralLimit);
  }
  const Eigen::Vector3d alpha = params_.gains.rate_p * error + params_.gains.rate_i * rate_integral_;
  return inertia_kgm2_.cwiseProduct(alpha) + w_B.cross(inertia_kgm2_.cwiseProduct(w_B));
}

std::array<double, 4> mix(const FcVehicle& v, double thrust_N, const Eigen::Vector3d& torque_Nm) {
  const double a = v.arm_length_m / std::sqrt(2.0);
  const double k_ratio = v.torque_coeff_Nm_per_radps2 / v.thrust_coeff_N_per_radps2;  // Q = k T
  const double t_max = v.thrust_coeff_N_per_radps2 * v.max_rotor_speed_radps * v.max_rotor_speed_radps;
  // Rotor positions (x, y) and yaw sign (torque on the body per newton of thrust / k_ratio).
  static constexpr double kX[4] = {+1, -1, +1, -1}, kY[4] = {-1, +1, +1, -1}, kYaw[4] = {-1, -1, +1, +1};
  auto solve = [&](double yaw_scale) {
    std::array<double, 4> t;
    for (int i = 0; i < 4; ++i) {
      // Inverse of: T = Σt, τx = Σ y_i t, τy = -Σ x_i t, τz = k Σ yaw_i t (each row orthogonal).
      t[i] = thrust_N / 4.0 + torque_Nm.x() * kY[i] / (4.0 * a) - torque_Nm.y() * kX[i] / (4.0 * a) +
             yaw_scale * torque_Nm.z() * kYaw[i] / (4.0 * k_ratio);
    }
    return t;
  };
  std::array<double, 4> t = solve(1.0);
  const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
  if (*lo < 0.0 || *hi > t_max) t = solve(0.0);  // saturated: keep thrust and attitude, drop yaw
  std::array<double, 4> throttle;
  for (int i = 0; i < 4; ++i) {
    const double ti = std::clamp(t[i], 0.0, t_max);
    throttle[i] = std::sqrt(ti / v.thrust_coeff_N_per_radps2) / v.max_rotor_speed_radps;
  }
  return throttle;
}

}  // namespace a3::bridge
