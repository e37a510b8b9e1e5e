// CRC-16-CCITT-FALSE and CRC-64-WE (see crc.hpp).
#include "bridge/dronecan/crc.hpp"

#include <array>

#include "bridge/can/crc16_slicing.hpp"

namespace a3::bridge {
namespace {

constexpr Crc16SlicingTables kCrc16Tables = crc16_slicing_tables(0x1021);

}  // namespace

uint16_t crc16_ccitt_false(const uint8_t* data, std::size_t size, uint16_t crc) {
  const auto& t = kCrc16Tables;
  std::size_t i = 0;
  // Eight bytes as eight independent lookups (crc16_slicing.hpp): the register's two bytes
  // meet the first two data bytes; the six after enter as data only.
  for (; i + 8 <= size; i += 8) {
    const uint8_t* d = data + i;
    crc = static_cast<uint16_t>(t[7][(crc >> 8) ^ d[0]] ^ t[6][(crc & 0xFFu) ^ d[1]] ^ t[5][d[2]] ^
                                t[4][d[3]] ^ t[3][d[4]] ^ t[2][d[5]] ^ t[1][d[6]] ^ t[0][d[7]]);
  }
  for (; i < size; ++i) crc = static_cast<uint16_t>((crc << 8) ^ t[0][((crc >> 8) ^ data[i]) & 0xFFu]);
  return crc;
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
