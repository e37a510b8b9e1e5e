// Bit-by-bit reference for a CAN frame's wire length (see frame_bits_reference.hpp).
#include "bridge/can/frame_bits_reference.hpp"

#include <algorithm>
#include <array>

namespace a3::bridge {
namespace {

// Bits of a frame from SOF to the end of the CRC, MSB first.
class BitSequence {
 public:
  void push(uint32_t value, unsigned bits) {
    for (unsigned i = bits; i-- > 0;) push_bit((value >> i) & 1u);
  }
  void push_bit(unsigned bit) {
    if (bit != 0) bytes_[count_ / 8] = static_cast<uint8_t>(bytes_[count_ / 8] | (0x80u >> (count_ % 8)));
    ++count_;
  }
  bool bit(unsigned i) const { return (bytes_[i / 8] & (0x80u >> (i % 8))) != 0; }
  unsigned size() const { return count_; }
  const uint8_t* data() const { return bytes_.data(); }

 private:
  std::array<uint8_t, 20> bytes_{};  // at most 1+32+4+64+15 bits
  unsigned count_ = 0;
};

void push_header(const CanFrame& frame, unsigned dlc, BitSequence& bits) {
  bits.push_bit(0);  // SOF
  if (frame.extended) {
    bits.push(frame.id >> 18, 11);
    bits.push_bit(1);  // SRR
    bits.push_bit(1);  // IDE
    bits.push(frame.id & 0x3FFFF, 18);
    bits.push_bit(frame.remote ? 1 : 0);
    bits.push(0, 2);  // r1, r0
  } else {
    bits.push(frame.id & 0x7FF, 11);
    bits.push_bit(frame.remote ? 1 : 0);
    bits.push(0, 2);  // IDE, r0
  }
  bits.push(dlc, 4);
}

unsigned count_stuff_bits(const BitSequence& bits) {
  unsigned stuff_bits = 0;
  unsigned run = 0;
  bool last = false;
  for (unsigned i = 0; i < bits.size(); ++i) {
    const bool b = bits.bit(i);
    if (i > 0 && b == last) {
      ++run;
    } else {
      run = 1;
      last = b;
    }
    if (run == 5) {
      // The stuff bit has the opposite value and starts the next run.
      ++stuff_bits;
      last = !b;
      run = 1;
    }
  }
  return stuff_bits;
}

constexpr unsigned kFixedTailBits = 1 + 2 + 7 + 3;  // CRC delimiter, ACK slot+delimiter, EOF, IFS

}  // namespace

uint16_t can_crc15_reference(const uint8_t* bits, unsigned bit_count) {
  uint16_t crc = 0;
  for (unsigned i = 0; i < bit_count; ++i) {
    const unsigned in = (bits[i / 8] >> (7 - i % 8)) & 1u;
    const unsigned top = (crc >> 14) & 1u;
    crc = static_cast<uint16_t>((crc << 1) & 0x7FFF);
    if ((in ^ top) != 0) crc ^= 0x4599;
  }
  return crc;
}

unsigned can_frame_bits_reference(const CanFrame& frame, BitStuffing stuffing) {
  const unsigned data_bytes = frame.remote ? 0u : std::min<unsigned>(frame.size, 8);
  const unsigned dlc = std::min<unsigned>(frame.size, 8);
  const unsigned g = frame.extended ? 54 : 34;
  const unsigned stuffed_region = g + 8 * data_bytes;
  if (stuffing == BitStuffing::kNone) return stuffed_region + kFixedTailBits;
  if (stuffing == BitStuffing::kWorstCase) {
    return stuffed_region + kFixedTailBits + (stuffed_region - 1) / 4;
  }
  BitSequence bits;
  push_header(frame, dlc, bits);
  for (unsigned i = 0; i < data_bytes; ++i) bits.push(frame.data[i], 8);
  bits.push(can_crc15_reference(bits.data(), bits.size()), 15);
  return bits.size() + count_stuff_bits(bits) + kFixedTailBits;
}

}  // namespace a3::bridge
