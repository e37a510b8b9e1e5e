// CanFrame <-> struct can_frame and the cansend text form (see can_frame.hpp).
#include "bridge/can/can_frame.hpp"

#include <linux/can.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace a3::bridge {

static_assert(sizeof(struct can_frame) == kSocketCanFrameBytes);

bool CanFrame::operator==(const CanFrame& other) const {
  return id == other.id && extended == other.extended && remote == other.remote &&
         error == other.error && size == other.size &&
         std::equal(data.begin(), data.begin() + std::min<std::size_t>(size, 8),
                    other.data.begin());
}

void to_socketcan(const CanFrame& frame, struct can_frame& out) {
  std::memset(&out, 0, sizeof out);
  out.can_id = frame.extended ? (frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG : frame.id & CAN_SFF_MASK;
  if (frame.remote) out.can_id |= CAN_RTR_FLAG;
  if (frame.error) out.can_id |= CAN_ERR_FLAG;
  out.len = std::min<uint8_t>(frame.size, 8);
  std::memcpy(out.data, frame.data.data(), out.len);
}

std::optional<CanFrame> from_socketcan(const struct can_frame& in) {
  if (in.len > 8) return std::nullopt;
  CanFrame frame;
  frame.extended = (in.can_id & CAN_EFF_FLAG) != 0;
  frame.remote = (in.can_id & CAN_RTR_FLAG) != 0;
  frame.error = (in.can_id & CAN_ERR_FLAG) != 0;
  frame.id = in.can_id & (frame.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
  frame.size = in.len;
  std::memcpy(frame.data.data(), in.data, in.len);
  return frame;
}

void to_socketcan_bytes(const CanFrame& frame, uint8_t* out) {
  struct can_frame raw;
  to_socketcan(frame, raw);
  std::memcpy(out, &raw, sizeof raw);
}

std::optional<CanFrame> from_socketcan_bytes(const uint8_t* in, std::size_t size) {
  if (size != sizeof(struct can_frame)) return std::nullopt;
  struct can_frame raw;
  std::memcpy(&raw, in, sizeof raw);
  return from_socketcan(raw);
}

std::string to_cansend_string(const CanFrame& frame) {
  char head[16];
  std::snprintf(head, sizeof head, frame.extended ? "%08X#" : "%03X#",
                static_cast<unsigned>(frame.id));
  std::string text(head);
  if (frame.remote) return text + "R";
  for (std::size_t i = 0; i < frame.size && i < 8; ++i) {
    char byte[3];
    std::snprintf(byte, sizeof byte, "%02X", frame.data[i]);
    text += byte;
  }
  return text;
}

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string quote(std::string_view text) {
  std::string quoted;
  quoted += '\'';
  quoted += text;
  quoted += '\'';
  return quoted;
}

std::optional<CanFrame> fail(std::string* error, std::string reason) {
  if (error != nullptr) *error = std::move(reason);
  return std::nullopt;
}

}  // namespace

std::optional<CanFrame> parse_cansend_string(std::string_view text, std::string* error) {
  const auto hash = text.find('#');
  if (hash == std::string_view::npos) {
    return fail(error, quote(text) + ": expected ID#DATA (e.g. 1004062A#0102)");
  }
  const std::string_view id_text = text.substr(0, hash);
  std::string_view data_text = text.substr(hash + 1);
  if (id_text.size() != 3 && id_text.size() != 8) {
    return fail(error, quote(text) +
                           ": the ID needs 3 hex digits (standard) or 8 (extended)");
  }
  CanFrame frame;
  frame.extended = id_text.size() == 8;
  uint32_t id = 0;
  for (char c : id_text) {
    const int v = hex_value(c);
    if (v < 0) return fail(error, quote(text) + ": bad hex digit in the ID");
    id = (id << 4) | static_cast<uint32_t>(v);
  }
  if (id > (frame.extended ? 0x1FFFFFFFu : 0x7FFu)) {
    return fail(error, quote(text) + ": ID out of range");
  }
  frame.id = id;
  if (data_text == "R" || data_text == "r") {
    frame.remote = true;
    return frame;
  }
  std::string digits;
  for (char c : data_text) {
    if (c != '.') digits += c;
  }
  if (digits.size() % 2 != 0 || digits.size() > 16) {
    return fail(error, quote(text) + ": data must be 0 to 8 bytes of 2 hex digits");
  }
  for (std::size_t i = 0; i < digits.size(); i += 2) {
    const int hi = hex_value(digits[i]);
    const int lo = hex_value(digits[i + 1]);
    if (hi < 0 || lo < 0) return fail(error, quote(text) + ": bad hex digit in the data");
    frame.data[i / 2] = static_cast<uint8_t>(hi * 16 + lo);
  }
  frame.size = static_cast<uint8_t>(digits.size() / 2);
  return frame;
}

}  // namespace a3::bridge
