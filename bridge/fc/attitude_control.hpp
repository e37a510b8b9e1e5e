// Inner loops of the flight controller: attitude (quaternion error → body-rate setpoint), body
// rate (PI on the rate error → angular acceleration → torque), and the mixer that turns a
// collective thrust and three torques into four rotor throttles (quad-X, PX4 order: 0 front-right
// CCW, 1 rear-left CCW, 2 front-left CW, 3 rear-right CW), giving up yaw first when saturated.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

#include "bridge/fc/fc_params.hpp"

namespace a3::bridge {

class AttitudeController {
 public:
  explicit AttitudeController(const FcParams& params);

  // Body-rate setpoint to turn q_WB toward q_sp (yaw loop slower than roll and pitch).
  Eigen::Vector3d rate_setpoint(const Eigen::Quaterniond& q_WB, const Eigen::Quaterniond& q_sp) const;
  // Torque for the rate setpoint; dt_s advances the integrator (0: no integration).
  Eigen::Vector3d torque(const Eigen::Vector3d& w_B, const Eigen::Vector3d& w_sp, double dt_s);
  void reset_integrator() { rate_integral_.setZero(); }

 private:
  const FcParams& params_;
  Eigen::Vector3d inertia_kgm2_;
  Eigen::Vector3d rate_integral_ = Eigen::Vector3d::Zero();
};

// Throttles (0..1) for a collective thrust (N) and body torques (N m).
std::array<double, 4> mix(const FcVehicle& vehicle, double thrust_N, const Eigen::Vector3d& torque_Nm);

}  // namespace a3::bridge
