// Attitude helpers (state packing is inline in the header).
#include "dynamics/vehicle_state.hpp"

#include <algorithm>
#include <cmath>

namespace a3::dynamics {

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
