// Fuzz target "dronecan": received CAN frames through the transfer reassembler, then each
// completed transfer decoded by its message type, encoded back and decoded again.
// Input: byte 0 the receiver's node ID, byte 1 its session table size (1..8), then frame
// records: CAN ID (4 bytes, little-endian), a flags byte (low 4 bits: data length, clamped to
// 8; 0x10 remote, 0x20 error, 0x40 standard 11-bit ID), the data bytes, then the milliseconds
// since the previous frame (1 byte). fuzz/corpus/dronecan is made from tests/data/dronecan.
// Invariants: a transfer fits its type; a decoded payload encodes, and decodes to the same
// fields; the reassembler counts every frame.
#include <algorithm>
#include <string>

#include "bridge/dronecan/message_registry.hpp"
#include "bridge/dronecan/reassembler.hpp"
#include "fuzz/fuzz_target.hpp"
#include "fuzz/input_reader.hpp"

namespace {

namespace bridge = a3::bridge;

const bridge::DataTypeTable& receiver_types() {
  static const bridge::DataTypeTable table = [] {
    bridge::DataTypeTable t;
    bridge::add_all_message_types(t);
    // A service type, so that requests and responses take their own paths.
    t.add("a3.fuzz.Echo", bridge::TransferKind::kRequest, 1, 0x0123456789abcdefULL, 64);
    t.add("a3.fuzz.Echo", bridge::TransferKind::kResponse, 1, 0x0123456789abcdefULL, 64);
    return t;
  }();
  return table;
}

bridge::CanFrame next_frame(a3::fuzz::InputReader& in) {
  bridge::CanFrame frame;
  frame.id = in.u32();
  const std::uint8_t flags = in.byte();
  frame.remote = (flags & 0x10) != 0;
  frame.error = (flags & 0x20) != 0;
  frame.extended = (flags & 0x40) == 0;
  const a3::fuzz::Input data = in.bytes(std::min<std::size_t>(flags & 0x0f, 8));
  std::copy(data.begin(), data.end(), frame.data.begin());
  frame.size = static_cast<std::uint8_t>(data.size());
  return frame;
}

std::string fields_text(const nlohmann::json& fields) {
  return fields.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void decode_round_trip(const bridge::ReceivedTransfer& transfer) {
  // An anonymous transfer carries only the two low bits of its type ID: its type is unknown.
  const std::size_t max_size = transfer.type != nullptr ? transfer.type->max_payload_bytes : 7;
  a3::fuzz::require(transfer.size <= max_size, "a transfer larger than its type allows");
  if (transfer.type == nullptr || transfer.header.kind != bridge::TransferKind::kMessage) return;
  const bridge::MessageTypeEntry* entry = bridge::find_message_type(transfer.header.data_type_id);
  if (entry == nullptr) return;
  nlohmann::json fields;
  std::string error;
  if (!entry->decode_to_json(transfer.payload, transfer.size, fields, error)) return;
  bridge::Payload encoded;
  a3::fuzz::require(entry->encode_from_json(fields, encoded, error), "decoded fields that do not encode");
  nlohmann::json again;
  a3::fuzz::require(entry->decode_to_json(encoded.data(), encoded.size, again, error),
                    "an encoded payload that does not decode");
  a3::fuzz::require(fields_text(fields) == fields_text(again), "fields changed by encode + decode");
}

}  // namespace

A3_FUZZ_TARGET(dronecan) {
  a3::fuzz::InputReader in(input);
  bridge::ReassemblerConfig config;
  config.local_node_id = in.byte() & 0x7f;
  config.max_sessions = 1 + (in.byte() & 7);
  bridge::TransferReassembler reassembler(receiver_types(), config);
  std::int64_t now_us = 0;
  std::uint64_t frames = 0;
  while (!in.empty()) {
    const bridge::CanFrame frame = next_frame(in);
    now_us += std::int64_t{in.byte()} * 1000;
    reassembler.expire(now_us);
    bridge::ReceivedTransfer transfer;
    ++frames;
    if (reassembler.accept(frame, now_us, transfer) == bridge::FrameVerdict::kTransferComplete) {
      decode_round_trip(transfer);
    }
  }
  a3::fuzz::require(reassembler.stats().frames == frames, "the reassembler lost count of frames");
}
