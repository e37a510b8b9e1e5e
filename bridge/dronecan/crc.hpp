// The two CRCs of DroneCAN: CRC-16-CCITT-FALSE for multi-frame transfers (seeded with the
// data type signature) and CRC-64-WE for data type signatures.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace a3::bridge {

// CRC-16-CCITT-FALSE (poly 0x1021, no reflection); start from 0xFFFF for a fresh CRC.
uint16_t crc16_ccitt_false(const uint8_t* data, std::size_t size, uint16_t crc = 0xFFFF);
// The CRC state after the signature's 8 little-endian bytes: the transfer CRC's seed. A
// constant expression, so that a message type's seed is computed once, by the compiler.
constexpr uint16_t transfer_crc_seed(uint64_t data_type_signature) {
  uint16_t crc = 0xFFFF;
  for (int byte = 0; byte < 8; ++byte) {
    crc = static_cast<uint16_t>(crc ^ (((data_type_signature >> (8 * byte)) & 0xFFu) << 8));
    for (int bit = 0; bit < 8; ++bit) {
      crc = static_cast<uint16_t>((crc & 0x8000u) != 0 ? (crc << 1) ^ 0x1021u : crc << 1);
    }
  }
  return crc;
}
// CRC of a multi-frame transfer's payload (the two bytes that start its first frame).
inline uint16_t transfer_crc(uint64_t data_type_signature, const uint8_t* payload, std::size_t size) {
  return crc16_ccitt_false(payload, size, transfer_crc_seed(data_type_signature));
}

// CRC-64-WE (poly 0x42F0E1EBA9EA3693, init and xorout all ones), incremental, as the
// DroneCAN DSDL tools use it; constructed from a previous value to extend it.
class Crc64We {
 public:
  Crc64We() = default;
  explicit Crc64We(uint64_t extend_from) : state_(extend_from ^ kMask) {}
  void add(const uint8_t* data, std::size_t size);
  void add(std::string_view text) {
    add(reinterpret_cast<const uint8_t*>(text.data()), text.size());
  }
  void add_u64_le(uint64_t value);
  uint64_t value() const { return state_ ^ kMask; }

 private:
  static constexpr uint64_t kMask = ~uint64_t{0};
  uint64_t state_ = kMask;
};

}  // namespace a3::bridge
