// Position and velocity control.
#include "bridge/fc/position_control.hpp"

#include <algorithm>
#include <cmath>

namespace a3::bridge {
namespace {
constexpr double kGravity_mps2 = 9.80665;
}

PositionController::PositionController(const FcParams& params) : params_(params) {}

Eigen::Vector3d PositionController::velocity_setpoint(const Eigen::Vector3d& p_W, const Eigen::Vector3d& p_sp,
                                                      double speed_limit_mps) const {
  const FcLimits& l = params_.limits;
  Eigen::Vector3d v = params_.gains.position_p * (p_sp - p_W);
  const double limit = std::min(speed_limit_mps, l.max_horizontal_speed_mps);
  const Eigen::Vector2d h(v.x(), v.y());
  if (h.norm() > limit) {
    v.x() *= limit / h.norm();
    v.y() *= limit / h.norm();
  }
  v.z() = std::clamp(v.z(), -l.max_descent_speed_mps, l.max_climb_speed_mps);
  return v;
}

ThrustSetpoint PositionController::thrust(const Eigen::Vector3d& v_W, const Eigen::Vector3d& v_sp,
                                          double yaw_sp_rad, double dt_s, bool integrate_xy) {
  const FcGains& g = params_.gains;
  const FcLimits& l = params_.limits;
  const Eigen::Vector3d error = v_sp - v_W;
  if (dt_s > 0.0) {
    Eigen::Vector3d step = error * dt_s;
    if (!integrate_xy) step.head<2>().setZero();
    velocity_integral_ += step;
    // Anti-windup: the integral alone may ask for at most half the horizontal acceleration
    // limit and 4 m/s² vertically.
    const double ixy = 0.5 * l.max_horizontal_accel_mps2 / std::max(g.velocity_i, 1e-9);
    const double iz = 4.0 / std::max(g.velocity_i, 1e-9);
    velocity_integral_.x() = std::clamp(velocity_integral_.x(), -ixy, ixy);
    velocity_integral_.y() = std::clamp(velocity_integral_.y(), -ixy, ixy);
    velocity_integral_.z() = std::clamp(velocity_integral_.z(), -iz, iz);
  }
  Eigen::Vector3d a = g.velocity_p * error + g.velocity_i * velocity_integral_;
  // Limit horizontal acceleration, and the tilt that the remaining vertical thrust allows.
  const double az = std::max(a.z() + kGravity_mps2, 0.2 * kGravity_mps2);
  const double tilt_limit = std::min(l.max_horizontal_accel_mps2, az * std::tan(l.max_tilt_deg * M_PI / 180.0));
  Eigen::Vector2d ah(a.x(), a.y());
  if (ah.norm() > tilt_limit) ah *= tilt_limit / ah.norm();
  const Eigen::Vector3d f = params_.vehicle.mass_kg * Eigen::Vector3d(ah.x(), ah.y(), az);
  // Body z along the thrust; heading from the yaw setpoint.
  const Eigen::Vector3d z_B = f.normalized();
  const Eigen::Vector3d x_heading(std::cos(yaw_sp_rad), std::sin(yaw_sp_rad), 0.0);
  Eigen::Vector3d y_B = z_B.cross(x_heading).normalized();
  const Eigen::Vector3d x_B = y_B.cross(z_B);
  Eigen::Matrix3d R;
  R.col(0) = x_B;
  R.col(1) = y_B;
  R.col(2) = z_B;
  ThrustSetpoint out;
  out.q_sp = Eigen::Quaterniond(R).normalized();
  out.thrust_N = f.norm();
  return out;
}

}  // namespace a3::bridge
