// CRC-16-CCITT-FALSE and CRC-64-WE (see crc.hpp).
#include "bridge/dronecan/crc.hpp"

#include <array>

namespace a3::bridge {
namespace {

// kCrc16Tables[k][i]: the CRC register after byte i (entering an all-zero register) and then k
// zero bytes. Eight bytes are then eight independent lookups instead of a chain of eight.
constexpr std::array<std::array<uint16_t, 256>, 8> make_crc16_tables() {
  std::array<std::array<uint16_t, 256>, 8> tables{};
  for (unsigned i = 0; i < 256; ++i) {
    uint16_t crc = static_cast<uint16_t>(i << 8);
    for (int bit = 0; bit < 8; ++bit) {
      crc = static_cast<uint16_t>((crc & 0x8000u) != 0 ? (crc << 1) ^ 0x1021u : crc << 1);
    }
    tables[0][i] = crc;
  }
  for (unsigned k = 1; k < 8; ++k) {
    for (unsigned i = 0; i < 256; ++i) {
      const uint16_t previous = tables[k - 1][i];
      tables[k][i] = static_cast<uint16_t>((previous << 8) ^ tables[0][previous >> 8]);
    }
  }
  return tables;
}

constexpr auto kCrc16Tables = make_crc16_tables();

}  // namespace

uint16_t crc16_ccitt_false(const uint8_t* data, std::size_t size, uint16_t crc) {
  const auto& t = kCrc16Tables;
  std::size_t i = 0;
  // The register's two bytes meet the first two data bytes; the six after enter as data only.
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
