// Tables for taking a most-significant-bit-first CRC with a 16-bit register several bytes at a
// time ("slicing"): the register's value is linear in what entered it, so n bytes are n
// independent table lookups XORed together instead of a chain of n dependent ones. A narrower
// CRC (CAN's CRC-15) uses them with its register and polynomial shifted to the left edge.
// Used by DroneCAN's transfer CRC-16 and by the CAN frame's CRC-15 (frame_timing.cpp).
#pragma once

#include <array>
#include <cstdint>

namespace a3::bridge {

using Crc16SlicingTables = std::array<std::array<uint16_t, 256>, 8>;

// tables[k][i]: the register after byte i entered an all-zero register and k zero bytes
// followed, for the given (left-aligned) polynomial.
constexpr Crc16SlicingTables crc16_slicing_tables(uint16_t polynomial) {
  Crc16SlicingTables tables{};
  for (unsigned i = 0; i < 256; ++i) {
    uint16_t crc = static_cast<uint16_t>(i << 8);
    for (int bit = 0; bit < 8; ++bit) {
      crc = static_cast<uint16_t>((crc & 0x8000u) != 0 ? (crc << 1) ^ polynomial : crc << 1);
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

}  // namespace a3::bridge
