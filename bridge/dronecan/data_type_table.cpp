// Known data types of a receiver (see data_type_table.hpp).
#include "bridge/dronecan/data_type_table.hpp"

#include <algorithm>
#include <stdexcept>

#include "bridge/dronecan/crc.hpp"

namespace a3::bridge {

void DataTypeTable::add(std::string full_name, TransferKind kind, uint16_t data_type_id,
                        uint64_t signature, std::size_t max_payload_bytes) {
  if (max_payload_bytes > kMaxTransferPayloadBytes) {
    throw std::invalid_argument(full_name + ": maximum payload " +
                                std::to_string(max_payload_bytes) + " bytes exceeds " +
                                std::to_string(kMaxTransferPayloadBytes));
  }
  const uint32_t k = key(kind, data_type_id);
  const auto [it, inserted] = entries_.try_emplace(k);
  if (!inserted) {
    if (it->second.full_name == full_name && it->second.signature == signature) return;
    throw std::invalid_argument("data type ID " + std::to_string(data_type_id) + " is " +
                                it->second.full_name + ", cannot also be " + full_name);
  }
  it->second = Entry{std::move(full_name), kind,
                     data_type_id,        signature,
                     transfer_crc_seed(signature), max_payload_bytes};
  index_.insert(index_position(k), {k, &it->second});
}

std::vector<std::pair<uint32_t, const DataTypeTable::Entry*>>::const_iterator DataTypeTable::index_position(
    uint32_t k) const {
  return std::lower_bound(index_.begin(), index_.end(), k,
                          [](const auto& item, uint32_t value) { return item.first < value; });
}

const DataTypeTable::Entry* DataTypeTable::find(TransferKind kind, uint16_t data_type_id) const {
  const uint32_t k = key(kind, data_type_id);
  const auto it = index_position(k);
  return it != index_.end() && it->first == k ? it->second : nullptr;
}

std::vector<DataTypeTable::Entry> DataTypeTable::entries() const {
  std::vector<Entry> out;
  out.reserve(entries_.size());
  for (const auto& [k, entry] : entries_) out.push_back(entry);
  std::sort(out.begin(), out.end(), [](const Entry& a, const Entry& b) {
    return a.kind != b.kind ? a.kind < b.kind : a.data_type_id < b.data_type_id;
  });
  return out;
}

}  // namespace a3::bridge
