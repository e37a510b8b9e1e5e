// Run-time table of every message type in messages.hpp: its DSDL identity plus type-erased
// JSON encode/decode, for tools that pick a type by name or data type ID (the CAN monitor,
// `a3rig can send`, the test-vector tests).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "bridge/dronecan/data_type_table.hpp"
#include "bridge/dronecan/dsdl_types.hpp"
#include "bridge/dronecan/serialization.hpp"

namespace a3::bridge {

struct MessageTypeEntry {
  DataTypeInfo info;
  // Computed from the C++ layout declaration (dsdl_layout.hpp), for the drift tests.
  std::string (*normalized_definition)();
  uint64_t (*layout_signature)();
  unsigned (*layout_max_bit_length)();
  // Payload -> JSON object of its fields; false with a reason in error when it does not decode.
  bool (*decode_to_json)(const uint8_t* data, std::size_t size, nlohmann::json& out,
                         std::string& error);
  // JSON object of fields -> payload; false with a reason (naming the field) when invalid.
  bool (*encode_from_json)(const nlohmann::json& fields, Payload& out, std::string& error);
};

// Top-level message types (with a default data type ID), in messages.hpp order.
const std::vector<MessageTypeEntry>& message_types();
// Nested types (no data type ID of their own).
const std::vector<MessageTypeEntry>& nested_message_types();
// By full name ("uavcan.equipment.esc.RawCommand") or by the part after the last dot when
// that is unambiguous ("RawCommand"); nullptr when unknown.
const MessageTypeEntry* find_message_type(std::string_view name);
const MessageTypeEntry* find_message_type(uint16_t data_type_id);
// Adds every top-level message type to a receiver's table.
void add_all_message_types(DataTypeTable& table);

}  // namespace a3::bridge
