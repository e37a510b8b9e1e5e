// Messages and malformed byte strings shared by the bus suites.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "a3lcm/episode_event_t.hpp"
#include "a3lcm/link_message_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"

namespace a3::test {

inline a3lcm::vehicle_state_t make_state(int64_t utime_us) {
  a3lcm::vehicle_state_t m{};
  m.utime_us = utime_us;
  for (int i = 0; i < 3; ++i) {
    m.p_W_m[i] = 10.0 * (i + 1) + 0.5;
    m.v_W_mps[i] = -1.25 * (i + 1);
    m.w_B_radps[i] = 0.01 * (i + 1);
    m.a_B_mps2[i] = 9.81 / (i + 1);
    m.wind_W_mps[i] = 2.0 + i;
  }
  m.q_WB[0] = 0.5;
  m.q_WB[1] = -0.5;
  m.q_WB[2] = 0.5;
  m.q_WB[3] = -0.5;
  for (int i = 0; i < 4; ++i) m.rotor_speed_radps[i] = 700.0 + i;
  m.battery_pct = 77.5;
  m.battery_voltage_v = 15.1;
  m.power_w = 250.25;
  m.mass_kg = 1.5;
  m.on_ground = false;
  m.crashed = true;
  return m;
}

inline a3lcm::link_message_t make_link_message(int64_t id, const std::string& text) {
  a3lcm::link_message_t m{};
  m.utime_us = id * 10;
  m.sent_utime_us = id * 10;
  m.message_id = id;
  m.sender = "test";
  m.kind = "mcp_call";
  m.slice = "eMBB";
  m.payload.assign(text.begin(), text.end());
  m.payload_length = static_cast<int32_t>(m.payload.size());
  m.payload_size_bytes = m.payload_length;
  return m;
}

template <typename Msg>
std::vector<uint8_t> encode_bytes(const Msg& msg) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// Bytes with the right fingerprint for episode_event_t whose first string claims a length
// of 0 (LCM counts the terminating NUL, so a valid length is >= 1). lcm-gen's decoder does
// not check this and ends up asking std::string for a negative length.
inline std::vector<uint8_t> episode_event_with_zero_string_length() {
  a3lcm::episode_event_t m{};
  m.utime_us = 1;
  m.turn = 2;
  m.speaker = "agent";
  m.kind = "k";
  m.status = "s";
  m.detail_json = "{}";
  std::vector<uint8_t> bytes = encode_bytes(m);
  // hash (8) + utime_us (8) + turn (4), then the big-endian int32 length of `speaker`.
  std::memset(bytes.data() + 20, 0, 4);
  return bytes;
}

// link_message_t with a negative payload_length (the field right before the payload).
inline std::vector<uint8_t> link_message_with_negative_payload_length() {
  std::vector<uint8_t> bytes = encode_bytes(make_link_message(5, "abc"));
  // The payload (3 bytes) is last; payload_length is the int32 before it.
  const std::size_t at = bytes.size() - 3 - 4;
  const uint8_t minus_one[4] = {0xFF, 0xFF, 0xFF, 0xFF};
  std::memcpy(bytes.data() + at, minus_one, 4);
  return bytes;
}

}  // namespace a3::test
