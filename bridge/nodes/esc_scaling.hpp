// The ESC command scale on CAN: uavcan.equipment.esc.RawCommand carries, per rotor, an int14
// where 0 stops the motor and 8191 is full speed; negative values (reverse) are not used by a
// multirotor. The rig's actuator_cmd_t throttle is the same command as a fraction 0..1.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "bridge/dronecan/msg/esc.hpp"

namespace a3::bridge {

inline constexpr int16_t kEscRawFull = EscRawCommand::kMax;  // 8191

// Throttle 0..1 (clamped; NaN gives 0) to the raw command.
inline int16_t throttle_to_esc_raw(double throttle) {
  if (!(throttle > 0.0)) return 0;
  return static_cast<int16_t>(std::lround(std::min(throttle, 1.0) * kEscRawFull));
}

// Raw command to throttle 0..1; negative (reverse) commands give 0.
inline double esc_raw_to_throttle(int16_t raw) {
  return raw <= 0 ? 0.0 : static_cast<double>(raw) / kEscRawFull;
}

}  // namespace a3::bridge
