// CRC-16-CCITT-FALSE and CRC-64-WE (see crc.hpp).
#include "bridge/dronecan/crc.hpp"

#include <array>

namespace a3::bridge {
namespace {

constexpr std::array<uint16_t, 256> make_crc16_table() {
  std::array<uint16_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) {
    uint16_t crc = static_cast<uint16_t>(i << 8);
    for (int bit = 0; bit < 8; ++bit) {
      crc = static_cast<uint16_t>((crc & 0x8000u) != 0 ? (crc << 1) ^ 0x1021u : crc << 1);
    }
    table[i] = crc;
  }
  return table;
}

constexpr std::array<uint16_t, 256> kCrc16Table = make_crc16_table();

}  // namespace

uint16_t crc16_ccitt_false(const uint8_t* data, std::size_t size, uint16_t crc) {
  for (std::size_t i = 0; i < size; ++i) {
    crc = static_cast<uint16_t>((crc << 8) ^ kCrc16Table[((crc >> 8) ^ data[i]) & 0xFFu]);
  }
  return crc;
}

uint16_t transfer_crc_seed(uint64_t data_type_signature) {
  uint8_t bytes[8];
  for (int i = 0; i < 8; ++i) bytes[i] = static_cast<uint8_t>(data_type_signature >> (8 * i));
  return crc16_ccitt_false(bytes, sizeof bytes);
}

uint16_t transfer_crc(uint64_t data_type_signature, const uint8_t* payload, std::size_t size) {
  return crc16_ccitt_false(payload, size, transfer_crc_seed(data_type_signature));
}

void Crc64We::add(const uint8_t* data, std::size_t size) {
  constexpr uint64_t kPoly = 0x42F0E1EBA9EA3693ULL;
  for (std::size_t i = 0; i < size; ++i) {
    state_ ^= static_cast<uint64_t>(data[i]) << 56;
    for (int bit = 0; bit < 8; ++bit) {
      state_ = (state_ & (uint64_t{1} << 63)) != 0 ? (state_ << 1) ^ kPoly : state_ << 1;
    }
  }
}

void Crc64We::add_u64_le(uint64_t value) {
  uint8_t bytes[8];
  for (int i = 0; i < 8; ++i) bytes[i] = static_cast<uint8_t>(value >> (8 * i));
  add(bytes, sizeof bytes);
}

}  // namespace a3::bridge
