// Quadrotor equations of motion.
#include "dynamics/quadrotor_model.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace a3::dynamics {
namespace {

// wrench(), in a function of this file so that derivatives() inlines it (the library is built
// position-independent: a public member function could be interposed, so it is not inlined).
Wrench wrench_of(const QuadrotorModel& model, const VehicleState& s, const Eigen::Vector3d& wind_W_mps) {
  const VehicleParams& params = model.params();
  const std::array<Eigen::Vector3d, 4>& rotor_p_B = model.rotor_positions_B_m();
  const Eigen::Quaterniond q = s.q_WB.normalized();
  Wrench out;
  double thrust_N = 0.0;
  double yaw_torque_Nm = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double w2 = s.rotor_speed_radps[i] * s.rotor_speed_radps[i];
    const double t = params.rotor.thrust_coeff_N_per_radps2 * w2;
    thrust_N += t;
    // r × (0, 0, T) = (r_y T, -r_x T, 0)
    out.torque_B_Nm.x() += rotor_p_B[i].y() * t;
    out.torque_B_Nm.y() -= rotor_p_B[i].x() * t;
    // A rotor spinning CCW (+z) is dragged CW by the air; the motor pushes the body CW too.
    yaw_torque_Nm -= QuadrotorModel::kSpin[i] * params.rotor.drag_torque_coeff_Nm_per_radps2 * w2;
  }
  out.torque_B_Nm.z() += yaw_torque_Nm;
  out.torque_B_Nm -= params.aero.angular_drag_Nms_per_rad * s.w_B_radps;

  const Eigen::Vector3d v_air = s.v_W_mps - wind_W_mps;
  const double quadratic = 0.5 * kAirDensity_kgpm3 * params.aero.drag_cdA_m2 * v_air.norm();
  out.force_W_N = q * Eigen::Vector3d(0, 0, thrust_N) - params.aero.linear_drag_Ns_per_m * v_air -
                  quadratic * v_air + Eigen::Vector3d(0, 0, -model.mass_kg() * kGravity_mps2);
  return out;
}

}  // namespace

QuadrotorModel::QuadrotorModel(VehicleParams params)
    : params_(std::move(params)),
      mass_kg_(params_.total_mass_kg()),
      inertia_kgm2_(params_.inertia_xx_kgm2, params_.inertia_yy_kgm2, params_.inertia_zz_kgm2) {
  const double a = params_.arm_length_m / std::sqrt(2.0);
  rotor_p_B_ = {Eigen::Vector3d(+a, -a, 0), Eigen::Vector3d(-a, +a, 0), Eigen::Vector3d(+a, +a, 0),
                Eigen::Vector3d(-a, -a, 0)};
  const double disk_area_m2 = M_PI * params_.rotor.radius_m * params_.rotor.radius_m;
  induced_power_factor_ = 1.0 / (params_.rotor.figure_of_merit * std::sqrt(2.0 * kAirDensity_kgpm3 * disk_area_m2));
}

Wrench QuadrotorModel::wrench(const VehicleState& s, const Eigen::Vector3d& wind_W_mps) const {
  return wrench_of(*this, s, wind_W_mps);
}

Eigen::Vector3d QuadrotorModel::specific_force_B_mps2(const VehicleState& s,
                                                      const Eigen::Vector3d& wind_W_mps) const {
  const Wrench w = wrench_of(*this, s, wind_W_mps);
  const Eigen::Vector3d non_gravity_W = w.force_W_N + Eigen::Vector3d(0, 0, mass_kg_ * kGravity_mps2);
  return s.q_WB.normalized().conjugate() * (non_gravity_W / mass_kg_);
}

double QuadrotorModel::rotor_speed_after(double speed, double command, double dt_s) const {
  return command + (speed - command) * std::exp(-dt_s / lag_time_constant_s(speed, command));
}

void QuadrotorModel::derivatives(const double* y, const RotorSpeeds& command,
                                 const Eigen::Vector3d& wind_W_mps, bool on_ground,
                                 double* dydt) const {
  // The rotor speeds are clamped at 0 in place, after their lag used the raw values: the
  // state is copied once per evaluation.
  VehicleState s = unpack_state(y);
  for (int i = 0; i < 4; ++i) {
    dydt[index::kRotor + i] = rotor_acceleration_radps2(s.rotor_speed_radps[i], command[i]);
    s.rotor_speed_radps[i] = std::max(0.0, s.rotor_speed_radps[i]);
  }
  dydt[index::kEnergy] = electrical_power_W(s.rotor_speed_radps);
  if (on_ground) {
    for (int i = 0; i < index::kRotor; ++i) dydt[i] = 0.0;
    return;
  }
  const Wrench w = wrench_of(*this, s, wind_W_mps);
  const Eigen::Vector3d a_W = w.force_W_N / mass_kg_;
  const Eigen::Vector3d& om = s.w_B_radps;
  const Eigen::Vector3d Iw = inertia_kgm2_.cwiseProduct(om);
  const Eigen::Vector3d dw = (w.torque_B_Nm - om.cross(Iw)).cwiseQuotient(inertia_kgm2_);
  // q̇ = ½ q ⊗ (0, ω), plus a term pulling |q| back to 1 (it does not change the attitude).
  const Eigen::Quaterniond& q = s.q_WB;
  const double norm_error = 1.0 - q.squaredNorm();
  constexpr double kNormGain = 1.0;
  const double qw = q.w(), qx = q.x(), qy = q.y(), qz = q.z();
  dydt[index::kQ + 0] = 0.5 * (-qx * om.x() - qy * om.y() - qz * om.z()) + kNormGain * norm_error * qw;
  dydt[index::kQ + 1] = 0.5 * (qw * om.x() + qy * om.z() - qz * om.y()) + kNormGain * norm_error * qx;
  dydt[index::kQ + 2] = 0.5 * (qw * om.y() - qx * om.z() + qz * om.x()) + kNormGain * norm_error * qy;
  dydt[index::kQ + 3] = 0.5 * (qw * om.z() + qx * om.y() - qy * om.x()) + kNormGain * norm_error * qz;
  for (int i = 0; i < 3; ++i) {
    dydt[index::kP + i] = s.v_W_mps[i];
    dydt[index::kV + i] = a_W[i];
    dydt[index::kW + i] = dw[i];
  }
}

double QuadrotorModel::hover_speed_radps() const {
  return std::sqrt(weight_N() / (4.0 * params_.rotor.thrust_coeff_N_per_radps2));
}

double QuadrotorModel::hover_throttle() const {
  return hover_speed_radps() / params_.rotor.max_speed_radps;
}

}  // namespace a3::dynamics
