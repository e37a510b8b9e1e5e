// How long a classic CAN frame occupies the wire: its bit count including bit stuffing,
// CRC delimiter, ACK, end of frame and the 3-bit intermission, and the arbitration order.
// Stuffing is computed exactly from the frame's bits (a stuff bit after every five equal
// bits from SOF to the end of the CRC, whose 15 bits are computed too), or worst case
// (Davis et al. 2007: floor((g + 8n - 1) / 4) stuff bits) when asked.
#pragma once

#include <cstdint>

#include "bridge/can/can_frame.hpp"

namespace a3::bridge {

enum class BitStuffing : uint8_t {
  kExact,      // the frame's own stuff bits (default)
  kWorstCase,  // the most any frame of that length can have
  kNone,       // no stuff bits (lower bound)
};

// Bits on the wire for this frame, intermission included. E.g. an 8-byte extended frame
// is 131 bits without stuffing and at most 160 with it.
unsigned can_frame_bits(const CanFrame& frame, BitStuffing stuffing = BitStuffing::kExact);

// The CAN CRC-15 (polynomial 0x4599) over a sequence of bits given MSB-first in bytes.
uint16_t can_crc15(const uint8_t* bits_msb_first, unsigned bit_count);

// Arbitration key: the frame with the lower key wins the bus (dominant 0 bits first).
// Between extended data frames it orders by CAN ID; a standard frame beats an extended
// frame with the same 11-bit base ID; a data frame beats a remote frame with the same ID.
uint32_t can_arbitration_key(const CanFrame& frame);

}  // namespace a3::bridge
