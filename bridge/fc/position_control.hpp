// Outer loops of the flight controller: position (P) → velocity setpoint (speed-limited) →
// velocity (PI) → acceleration → thrust vector → attitude setpoint and collective thrust.
// Horizontal acceleration is limited, and so is the tilt; altitude control has priority.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "bridge/fc/fc_params.hpp"

namespace a3::bridge {

struct ThrustSetpoint {
  Eigen::Quaterniond q_sp = Eigen::Quaterniond::Identity();
  double thrust_N = 0.0;
};

class PositionController {
 public:
  explicit PositionController(const FcParams& params);

  // Velocity setpoint toward a position setpoint, horizontal speed ≤ speed_limit_mps.
  Eigen::Vector3d velocity_setpoint(const Eigen::Vector3d& p_W, const Eigen::Vector3d& p_sp,
                                    double speed_limit_mps) const;
  // Attitude and thrust for a velocity setpoint; dt_s advances the integrator.
  ThrustSetpoint thrust(const Eigen::Vector3d& v_W, const Eigen::Vector3d& v_sp, double yaw_sp_rad,
                        double dt_s, bool integrate_xy = true);
  void reset_integrator() { velocity_integral_.setZero(); }
  const Eigen::Vector3d& integral() const { return velocity_integral_; }

 private:
  const FcParams& params_;
  Eigen::Vector3d velocity_integral_ = Eigen::Vector3d::Zero();
};

}  // namespace a3::bridge
