// DroneCAN (UAVCAN v0) transfer framing on classic CAN: the 29-bit identifier (priority,
// data type ID, source node; service frames too), the tail byte (start, end, toggle,
// transfer ID), and splitting a payload into frames (a multi-frame transfer starts with the
// signature-seeded CRC-16, low byte first, then 7 payload bytes per frame).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bridge/can/can_frame.hpp"
#include "bridge/dronecan/crc.hpp"
#include "bridge/dronecan/serialization.hpp"

namespace a3::bridge {

enum class TransferKind : uint8_t { kMessage = 0, kRequest = 1, kResponse = 2 };

// Priorities: lower is more urgent (wins arbitration). DroneCAN's named levels.
inline constexpr uint8_t kPriorityHighest = 0, kPriorityHigh = 8, kPriorityMedium = 16,
                         kPriorityLow = 24, kPriorityLowest = 31;
inline constexpr uint8_t kMaxNodeId = 127;
inline constexpr uint8_t kTransferIdModulo = 32;

struct TransferHeader {
  uint8_t priority = kPriorityMedium;  // 0..31
  TransferKind kind = TransferKind::kMessage;
  uint16_t data_type_id = 0;           // messages 0..65535; services 0..255
  uint8_t source_node_id = 0;          // 1..127; 0 = anonymous (single-frame messages only)
  uint8_t destination_node_id = 0;     // services only, 1..127
  uint8_t transfer_id = 0;             // 0..31

  bool operator==(const TransferHeader&) const = default;
};

// The 29-bit CAN ID of a transfer (anonymous messages use discriminator 0 here).
// Out-of-range fields are masked to their widths; check_header() says what is wrong first.
uint32_t make_can_id(const TransferHeader& header);
// What a 29-bit ID says (transfer_id left 0). *anonymous is set for anonymous messages,
// whose data_type_id holds only the two low bits of the type ID. Inline: every received
// frame is parsed, and a caller reads only some of the fields.
inline TransferHeader parse_can_id(uint32_t id, bool* anonymous = nullptr) {
  TransferHeader h;
  h.priority = static_cast<uint8_t>((id >> 24) & 0x1F);
  h.source_node_id = static_cast<uint8_t>(id & 0x7F);
  const bool service = (id & (1u << 7)) != 0;
  bool is_anonymous = false;
  if (!service) {
    h.kind = TransferKind::kMessage;
    if (h.source_node_id == 0) {
      is_anonymous = true;
      h.data_type_id = static_cast<uint16_t>((id >> 8) & 0x3);
    } else {
      h.data_type_id = static_cast<uint16_t>((id >> 8) & 0xFFFF);
    }
  } else {
    h.kind = (id & (1u << 15)) != 0 ? TransferKind::kRequest : TransferKind::kResponse;
    h.data_type_id = static_cast<uint16_t>((id >> 16) & 0xFF);
    h.destination_node_id = static_cast<uint8_t>((id >> 8) & 0x7F);
  }
  if (anonymous != nullptr) *anonymous = is_anonymous;
  return h;
}
// "" when the header can be sent, else what is wrong ("priority 40 > 31").
std::string check_header(const TransferHeader& header);

struct TailByte {
  bool start_of_transfer = false;
  bool end_of_transfer = false;
  bool toggle = false;
  uint8_t transfer_id = 0;

  static TailByte parse(uint8_t byte) {
    return {(byte & 0x80) != 0, (byte & 0x40) != 0, (byte & 0x20) != 0,
            static_cast<uint8_t>(byte & 0x1F)};
  }
  uint8_t pack() const {
    return static_cast<uint8_t>((start_of_transfer ? 0x80 : 0) | (end_of_transfer ? 0x40 : 0) |
                                (toggle ? 0x20 : 0) | (transfer_id & 0x1F));
  }
};

// Number of frames a payload of this size takes.
std::size_t transfer_frame_count(std::size_t payload_size);

// Appends the frames of one transfer to out (out is not cleared). crc_seed (transfer_crc_seed
// of the data type's signature) seeds the CRC of multi-frame transfers.
void append_transfer_frames_seeded(const TransferHeader& header, uint16_t crc_seed, const uint8_t* payload,
                                   std::size_t size, std::vector<CanFrame>& out);
inline void append_transfer_frames(const TransferHeader& header, uint64_t data_type_signature,
                                   const uint8_t* payload, std::size_t size, std::vector<CanFrame>& out) {
  append_transfer_frames_seeded(header, transfer_crc_seed(data_type_signature), payload, size, out);
}

// The header of a message of type Msg (its default data type ID).
template <DsdlCompound Msg>
TransferHeader message_header(uint8_t source_node_id, uint8_t transfer_id,
                              uint8_t priority = kPriorityMedium) {
  TransferHeader header;
  header.priority = priority;
  header.kind = TransferKind::kMessage;
  header.data_type_id = Msg::kType.default_dtid;
  header.source_node_id = source_node_id;
  header.transfer_id = transfer_id;
  return header;
}

// Serializes msg and appends its frames to out. payload is scratch space (reused to avoid
// allocation); on failure nothing is appended.
template <DsdlCompound Msg>
CodecStatus append_message_frames(const Msg& msg, const TransferHeader& header, Payload& payload,
                                  std::vector<CanFrame>& out) {
  const CodecStatus status = encode_payload(msg, payload);
  if (status.ok()) {
    constexpr uint16_t kCrcSeed = transfer_crc_seed(Msg::kType.signature);
    append_transfer_frames_seeded(header, kCrcSeed, payload.data(), payload.size, out);
  }
  return status;
}

}  // namespace a3::bridge
