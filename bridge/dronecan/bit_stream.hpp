// Bit-level reader and writer for DSDL (UAVCAN v0) serialization. Bits are packed
// most-significant first; a scalar wider than 8 bits is stored as its little-endian bytes,
// the last partial byte holding the value's top bits (libcanard's canardEncodeScalar).
#pragma once

#include <cstddef>
#include <cstdint>

namespace a3::bridge {

class BitWriter {
 public:
  // The buffer must hold capacity_bytes; it is zeroed here.
  BitWriter(uint8_t* buffer, std::size_t capacity_bytes);

  // Appends the low bit_length (1..64) bits of value as a DSDL scalar.
  // Returns false (and writes nothing) when the buffer is full.
  bool write_scalar(uint64_t value, unsigned bit_length);
  // Appends bit_length zero bits (void fields).
  bool write_zeros(unsigned bit_length);

  std::size_t bit_offset() const { return bit_offset_; }
  std::size_t byte_size() const { return (bit_offset_ + 7) / 8; }

 private:
  void put_bits(uint8_t value, unsigned count);  // count 1..8, low bits of value, MSB first

  uint8_t* buffer_;
  std::size_t capacity_bits_;
  std::size_t bit_offset_ = 0;
};

class BitReader {
 public:
  BitReader(const uint8_t* data, std::size_t size_bytes)
      : data_(data), size_bits_(size_bytes * 8) {}

  // Reads a DSDL scalar of bit_length (1..64) bits, zero-extended.
  // Returns false (and consumes nothing) when fewer bits remain.
  bool read_unsigned(unsigned bit_length, uint64_t& value);
  // Same, sign-extended from bit_length bits.
  bool read_signed(unsigned bit_length, int64_t& value);
  bool skip(unsigned bit_length);

  std::size_t bit_offset() const { return bit_offset_; }
  std::size_t remaining_bits() const { return size_bits_ - bit_offset_; }

 private:
  uint8_t get_bits(unsigned count);  // count 1..8

  const uint8_t* data_;
  std::size_t size_bits_;
  std::size_t bit_offset_ = 0;
};

}  // namespace a3::bridge
