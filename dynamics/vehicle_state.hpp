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

void pack_state(const VehicleState& s, double* y);
VehicleState unpack_state(const double* y);

// Roll, pitch, yaw (rad) of q_WB, ZYX convention (yaw about world z, ENU).
Eigen::Vector3d roll_pitch_yaw_rad(const Eigen::Quaterniond& q_WB);
// The angle (rad) of the rotation between two attitudes.
double attitude_difference_rad(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

}  // namespace a3::dynamics
