// DroneCAN identifiers, tail bytes and frame splitting (see transfer.hpp).
#include "bridge/dronecan/transfer.hpp"

#include <algorithm>

#include "bridge/dronecan/crc.hpp"

namespace a3::bridge {

uint32_t make_can_id(const TransferHeader& h) {
  const uint32_t priority = static_cast<uint32_t>(h.priority & 0x1F) << 24;
  const uint32_t source = h.source_node_id & 0x7F;
  if (h.kind == TransferKind::kMessage) {
    if (source == 0) {  // anonymous: discriminator 0, two low bits of the type ID
      return priority | (static_cast<uint32_t>(h.data_type_id & 0x3) << 8);
    }
    return priority | (static_cast<uint32_t>(h.data_type_id) << 8) | source;
  }
  const uint32_t request = h.kind == TransferKind::kRequest ? 1u << 15 : 0u;
  return priority | (static_cast<uint32_t>(h.data_type_id & 0xFF) << 16) | request |
         (static_cast<uint32_t>(h.destination_node_id & 0x7F) << 8) | (1u << 7) | source;
}

std::string check_header(const TransferHeader& h) {
  if (h.priority > 31) return "priority " + std::to_string(h.priority) + " > 31";
  if (h.source_node_id > kMaxNodeId) {
    return "source node ID " + std::to_string(h.source_node_id) + " > 127";
  }
  if (h.transfer_id >= kTransferIdModulo) {
    return "transfer ID " + std::to_string(h.transfer_id) + " > 31";
  }
  if (h.kind != TransferKind::kMessage) {
    if (h.data_type_id > 255) {
      return "service type ID " + std::to_string(h.data_type_id) + " > 255";
    }
    if (h.source_node_id == 0) return "a service transfer needs a source node ID";
    if (h.destination_node_id == 0 || h.destination_node_id > kMaxNodeId) {
      return "service destination node ID " + std::to_string(h.destination_node_id) +
             " not in 1..127";
    }
  }
  return "";
}

std::size_t transfer_frame_count(std::size_t payload_size) {
  if (payload_size <= 7) return 1;
  return (payload_size + 2 + 6) / 7;
}

void append_transfer_frames_seeded(const TransferHeader& header, uint16_t crc_seed, const uint8_t* payload,
                                   std::size_t size, std::vector<CanFrame>& out) {
  CanFrame frame;
  frame.id = make_can_id(header);
  frame.extended = true;
  TailByte tail{true, false, false, static_cast<uint8_t>(header.transfer_id & 0x1F)};
  if (size <= 7) {
    std::copy(payload, payload + size, frame.data.begin());
    tail.end_of_transfer = true;
    frame.data[size] = tail.pack();
    frame.size = static_cast<uint8_t>(size + 1);
    out.push_back(frame);
    return;
  }
  const uint16_t crc = crc16_ccitt_false(payload, size, crc_seed);
  // The CRC travels as the first two bytes of the stream, low byte first: the first frame
  // holds it and 5 payload bytes, every other frame up to 7.
  frame.data[0] = static_cast<uint8_t>(crc & 0xFF);
  frame.data[1] = static_cast<uint8_t>(crc >> 8);
  std::size_t offset = 0;  // in the payload
  std::size_t room = 5, at = 2;
  while (offset < size) {
    const std::size_t chunk = std::min(room, size - offset);
    std::copy(payload + offset, payload + offset + chunk, frame.data.begin() + static_cast<std::ptrdiff_t>(at));
    offset += chunk;
    tail.end_of_transfer = offset == size;
    frame.data[at + chunk] = tail.pack();
    frame.size = static_cast<uint8_t>(at + chunk + 1);
    out.push_back(frame);
    tail.start_of_transfer = false;
    tail.toggle = !tail.toggle;
    room = 7;
    at = 0;
  }
}

}  // namespace a3::bridge
