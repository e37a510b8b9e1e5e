// State packing and attitude helpers.
#include "dynamics/vehicle_state.hpp"

#include <algorithm>
#include <cmath>

namespace a3::dynamics {

void pack_state(const VehicleState& s, double* y) {
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

VehicleState unpack_state(const double* y) {
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

Eigen::Vector3d roll_pitch_yaw_rad(const Eigen::Quaterniond& q) {
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  return {roll, pitch, yaw};
}

double attitude_difference_rad(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.normalized().angularDistance(b.normalized());
}

}  // namespace a3::dynamics
