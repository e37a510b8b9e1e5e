// One classic CAN 2.0 frame as the rig handles it, and its exact Linux SocketCAN form
// (struct can_frame, 16 bytes), which both transports carry.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

struct can_frame;  // <linux/can.h>

namespace a3::bridge {

struct CanFrame {
  uint32_t id = 0;         // 29-bit identifier when extended, 11-bit otherwise
  bool extended = true;    // CAN 2.0B extended frame (DroneCAN uses only these)
  bool remote = false;     // remote transmission request
  bool error = false;      // SocketCAN error frame
  uint8_t size = 0;        // data bytes, 0..8
  std::array<uint8_t, 8> data{};

  bool operator==(const CanFrame& other) const;
};

inline constexpr std::size_t kSocketCanFrameBytes = 16;  // sizeof(struct can_frame)

// struct can_frame from a frame (CAN_EFF_FLAG etc. set from the flags).
void to_socketcan(const CanFrame& frame, struct can_frame& out);
// A frame from a struct can_frame; nothing when its length is over 8 (not classic CAN).
std::optional<CanFrame> from_socketcan(const struct can_frame& in);
// The same through raw bytes (exactly kSocketCanFrameBytes).
void to_socketcan_bytes(const CanFrame& frame, uint8_t* out);
std::optional<CanFrame> from_socketcan_bytes(const uint8_t* in, std::size_t size);

// cansend / candump -L syntax: "1004062A#000280FFF7C020C5" (8 hex digits = extended),
// "123#R" for a remote frame.
std::string to_cansend_string(const CanFrame& frame);
// Parses that syntax; nothing (and a reason in *error) when it is not valid.
std::optional<CanFrame> parse_cansend_string(std::string_view text, std::string* error = nullptr);

}  // namespace a3::bridge
