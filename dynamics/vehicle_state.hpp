// The state of the simulated vehicle (world frame ENU, body frame FLU) and its packing into the
// flat array an ODE solver integrates.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

namespace a3::dynamics {

struct VehicleState {
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();      // centre of mass, world ENU
  Eigen::Vector3d v_W_mps = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  // body → world
  Eigen::Vector3d w_B_radps = Eigen::Vector3d::Zero();  // body rates, FLU
  std::array<double, 4> rotor_speed_radps{};
  double energy_used_J = 0.0;
};

// Flat layout: p(3) v(3) q(4: w x y z) w(3) rotors(4) energy(1).
inline constexpr int kStateSize = 18;
namespace index {
inline constexpr int kP = 0, kV = 3, kQ = 6, kW = 10, kRotor = 13, kEnergy = 17;
}

// Inline: unpack_state runs in every right-hand-side evaluation.
inline void pack_state(const VehicleState& s, double* y) {
  for (int i = 0; i < 3; ++i) {
    y[index::kP + i] = s.p_W_m[i];
    y[index::kV + i] = s.v_W_mps[i];
    y[index::kW + i] = s.w_B_radps[i];
  }
  y[index::kQ + 0] = s.q_WB.w();
  y[index::kQ + 1] = s.q_WB.x();
  y[index::kQ + 2] = s.q_WB.y();
  y[index::kQ + 3] = s.q_WB.z();
  for (int i = 0; i < 4; ++i) y[index::kRotor + i] = s.rotor_speed_radps[i];
  y[index::kEnergy] = s.energy_used_J;
}

inline VehicleState unpack_state(const double* y) {
  VehicleState s;
  for (int i = 0; i < 3; ++i) {
    s.p_W_m[i] = y[index::kP + i];
    s.v_W_mps[i] = y[index::kV + i];
    s.w_B_radps[i] = y[index::kW + i];
  }
  s.q_WB = Eigen::Quaterniond(y[index::kQ], y[index::kQ + 1], y[index::kQ + 2], y[index::kQ + 3]);
  for (int i = 0; i < 4; ++i) s.rotor_speed_radps[i] = y[index::kRotor + i];
  s.energy_used_J = y[index::kEnergy];
  return s;
}

// Roll, pitch, yaw (rad) of q_WB, ZYX convention (yaw about world z, ENU).
Eigen::Vector3d roll_pitch_yaw_rad(const Eigen::Quaterniond& q_WB);
// The angle (rad) of the rotation between two attitudes.
double attitude_difference_rad(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

}  // namespace a3::dynamics
