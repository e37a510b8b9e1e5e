// Frame conventions between the rig and DroneCAN: the rig's body frame is FLU and its world
// frame ENU (CONVENTIONS.md); DroneCAN's body frame is FRD (X forward, Y right, Z down) and
// GNSS velocity is NED. Both swaps are their own inverse.
#pragma once

#include <Eigen/Core>

namespace a3::bridge {

// Body FLU ↔ body FRD.
inline Eigen::Vector3d flu_frd(const Eigen::Vector3d& v) { return {v.x(), -v.y(), -v.z()}; }
// World ENU ↔ world NED.
inline Eigen::Vector3d enu_ned(const Eigen::Vector3d& v) { return {v.y(), v.x(), -v.z()}; }

}  // namespace a3::bridge
