// The data types a receiver knows: (kind, data type ID) -> signature (the CRC seed of its
// multi-frame transfers) and maximum payload size (the bound on reassembly memory).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bridge/dronecan/dsdl_types.hpp"
#include "bridge/dronecan/transfer.hpp"

namespace a3::bridge {

class DataTypeTable {
 public:
  struct Entry {
    std::string full_name;
    TransferKind kind = TransferKind::kMessage;
    uint16_t data_type_id = 0;
    uint64_t signature = 0;
    uint16_t crc_seed = 0;
    std::size_t max_payload_bytes = 0;
  };

  // Adds a message type under its default (or the given) data type ID. Adding the same type
  // twice is harmless; another type under a taken ID throws std::invalid_argument.
  template <DsdlCompound Msg>
  void add_message(uint16_t data_type_id = Msg::kType.default_dtid) {
    add(std::string(Msg::kType.full_name), TransferKind::kMessage, data_type_id,
        Msg::kType.signature, (Msg::kType.max_bit_length + 7) / 8);
  }
  void add(std::string full_name, TransferKind kind, uint16_t data_type_id, uint64_t signature,
           std::size_t max_payload_bytes);

  const Entry* find(TransferKind kind, uint16_t data_type_id) const;
  std::vector<Entry> entries() const;
  std::size_t size() const { return entries_.size(); }

 private:
  static uint32_t key(TransferKind kind, uint16_t data_type_id) {
    return (static_cast<uint32_t>(kind) << 16) | data_type_id;
  }
  // The first index_ item whose key is not less than k.
  std::vector<std::pair<uint32_t, const Entry*>>::const_iterator index_position(uint32_t k) const;
  std::unordered_map<uint32_t, Entry> entries_;  // stable addresses for find()'s pointers
  // (key, entry) sorted by key: find() runs for every received frame, a hash lookup costs more.
  std::vector<std::pair<uint32_t, const Entry*>> index_;
};

}  // namespace a3::bridge
