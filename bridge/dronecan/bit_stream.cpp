// DSDL bit packing (see bit_stream.hpp).
#include "bridge/dronecan/bit_stream.hpp"

#include <cstring>

namespace a3::bridge {

BitWriter::BitWriter(uint8_t* buffer, std::size_t capacity_bytes)
    : buffer_(buffer), capacity_bits_(capacity_bytes * 8) {
  std::memset(buffer_, 0, capacity_bytes);
}

void BitWriter::put_bits(uint8_t value, unsigned count) {
  const std::size_t byte = bit_offset_ / 8;
  const unsigned used = static_cast<unsigned>(bit_offset_ % 8);
  const unsigned free_bits = 8 - used;
  value = static_cast<uint8_t>(value & ((1u << count) - 1u));
  if (count <= free_bits) {
    buffer_[byte] = static_cast<uint8_t>(buffer_[byte] | (value << (free_bits - count)));
  } else {
    const unsigned spill = count - free_bits;
    buffer_[byte] = static_cast<uint8_t>(buffer_[byte] | (value >> spill));
    buffer_[byte + 1] = static_cast<uint8_t>(buffer_[byte + 1] | (value << (8 - spill)));
  }
  bit_offset_ += count;
}

bool BitWriter::write_scalar(uint64_t value, unsigned bit_length) {
  if (bit_length == 0 || bit_length > 64 || bit_offset_ + bit_length > capacity_bits_) {
    return false;
  }
  const unsigned full_bytes = bit_length / 8;
  if (bit_offset_ % 8 == 0) {
    uint8_t* out = buffer_ + bit_offset_ / 8;
    for (unsigned i = 0; i < full_bytes; ++i) out[i] = static_cast<uint8_t>(value >> (8 * i));
    bit_offset_ += 8u * full_bytes;
  } else {
    for (unsigned i = 0; i < full_bytes; ++i) put_bits(static_cast<uint8_t>(value >> (8 * i)), 8);
  }
  if (const unsigned rest = bit_length % 8; rest != 0) {
    put_bits(static_cast<uint8_t>(value >> (8 * full_bytes)), rest);
  }
  return true;
}

bool BitWriter::write_zeros(unsigned bit_length) {
  if (bit_offset_ + bit_length > capacity_bits_) return false;
  bit_offset_ += bit_length;  // the buffer was zeroed
  return true;
}

uint8_t BitReader::get_bits(unsigned count) {
  const std::size_t byte = bit_offset_ / 8;
  const unsigned used = static_cast<unsigned>(bit_offset_ % 8);
  const unsigned avail = 8 - used;
  unsigned value;
  if (count <= avail) {
    value = static_cast<unsigned>(data_[byte] >> (avail - count));
  } else {
    const unsigned spill = count - avail;
    value = static_cast<unsigned>(data_[byte] << spill) |
            static_cast<unsigned>(data_[byte + 1] >> (8 - spill));
  }
  bit_offset_ += count;
  return static_cast<uint8_t>(value & ((1u << count) - 1u));
}

bool BitReader::read_unsigned(unsigned bit_length, uint64_t& value) {
  if (bit_length == 0 || bit_length > 64 || bit_length > remaining_bits()) return false;
  const unsigned full_bytes = bit_length / 8;
  uint64_t result = 0;
  if (bit_offset_ % 8 == 0) {
    const uint8_t* in = data_ + bit_offset_ / 8;
    for (unsigned i = 0; i < full_bytes; ++i) result |= static_cast<uint64_t>(in[i]) << (8 * i);
    bit_offset_ += 8u * full_bytes;
  } else {
    for (unsigned i = 0; i < full_bytes; ++i) {
      result |= static_cast<uint64_t>(get_bits(8)) << (8 * i);
    }
  }
  if (const unsigned rest = bit_length % 8; rest != 0) {
    result |= static_cast<uint64_t>(get_bits(rest)) << (8 * full_bytes);
  }
  value = result;
  return true;
}

bool BitReader::read_signed(unsigned bit_length, int64_t& value) {
  uint64_t raw = 0;
  if (!read_unsigned(bit_length, raw)) return false;
  if (bit_length < 64 && (raw & (uint64_t{1} << (bit_length - 1))) != 0) {
    raw |= ~uint64_t{0} << bit_length;
  }
  value = static_cast<int64_t>(raw);
  return true;
}

bool BitReader::skip(unsigned bit_length) {
  if (bit_length > remaining_bits()) return false;
  bit_offset_ += bit_length;
  return true;
}

}  // namespace a3::bridge
