// Conversions between fc_command_t/fc_status_t, a3.fc.Command/Status and the fc's types.
#include "bridge/nodes/fc_messages.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace a3::bridge {

float to_float32(double value) {
  if (std::isnan(value)) return std::numeric_limits<float>::quiet_NaN();
  if (value > std::numeric_limits<float>::max()) return std::numeric_limits<float>::infinity();
  if (value < -std::numeric_limits<float>::max()) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

FcCommand fc_command_to_can(const a3lcm::fc_command_t& c) {
  FcCommand out;
  out.seq = c.seq;
  out.command = static_cast<uint8_t>(c.command);
  for (int i = 0; i < 3; ++i) out.target_W_m[i] = to_float32(c.target_W_m[i]);
  out.speed_limit_mps = to_float32(c.speed_limit_mps);
  out.yaw_deg = to_float32(c.yaw_deg);
  return out;
}

bool fc_command_has_nonfinite(const a3lcm::fc_command_t& c) {
  for (double v : c.target_W_m) {
    if (!std::isfinite(v)) return true;
  }
  return !std::isfinite(c.speed_limit_mps) || std::isinf(c.yaw_deg);
}

FlightCommand flight_command_from_can(const FcCommand& c) {
  FlightCommand out;
  out.seq = c.seq;
  // FlightCommandKind has int8 storage: codes above the last are kept (and refused as unknown).
  out.kind = static_cast<FlightCommandKind>(static_cast<int8_t>(c.command));
  out.target_W_m = Eigen::Vector3d(c.target_W_m[0], c.target_W_m[1], c.target_W_m[2]);
  out.speed_limit_mps = c.speed_limit_mps;
  out.yaw_deg = c.yaw_deg;
  return out;
}

FcStatus fc_status_to_can(const FlightStatus& s) {
  FcStatus out;
  out.mode = static_cast<uint8_t>(s.mode);
  out.armed = s.armed;
  out.failsafe = static_cast<uint8_t>(s.failsafe);
  for (int i = 0; i < 3; ++i) {
    out.p_W_m[i] = to_float32(s.p_W_m[i]);
    out.v_W_mps[i] = to_float32(s.v_W_mps[i]);
  }
  out.yaw_deg = to_float32(s.yaw_deg);
  out.battery_pct = to_float32(s.battery_pct);
  out.last_command_seq = s.last_command_seq;
  out.last_command_accepted = s.last_command_accepted;
  out.last_command_reason = static_cast<uint8_t>(s.last_refusal);
  return out;
}

a3lcm::fc_status_t fc_status_from_can(const FcStatus& s, int64_t utime_us) {
  a3lcm::fc_status_t out;
  out.utime_us = utime_us;
  out.mode = static_cast<int8_t>(s.mode);
  out.armed = s.armed;
  out.failsafe = static_cast<int8_t>(s.failsafe);
  for (int i = 0; i < 3; ++i) {
    out.p_W_m[i] = s.p_W_m[i];
    out.v_W_mps[i] = s.v_W_mps[i];
  }
  out.yaw_deg = s.yaw_deg;
  out.battery_pct = s.battery_pct;
  out.last_command_seq = s.last_command_seq;
  out.last_command_accepted = s.last_command_accepted;
  out.last_command_reason = std::string(fc_reason_text(s.last_command_reason));
  return out;
}

}  // namespace a3::bridge
