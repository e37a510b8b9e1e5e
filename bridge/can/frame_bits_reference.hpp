// The bit-by-bit reference for a CAN frame's on-wire length: every bit from SOF to the end
// of the CRC is laid out, the CRC-15 computed one bit at a time and the stuff bits counted
// one bit at a time. Slow and plain on purpose: the tests hold can_frame_bits (the fast,
// table-driven path in frame_timing.cpp) to it, bit for bit.
#pragma once

#include "bridge/can/can_frame.hpp"
#include "bridge/can/frame_timing.hpp"

namespace a3::bridge {

// The same contract as can_frame_bits.
unsigned can_frame_bits_reference(const CanFrame& frame, BitStuffing stuffing = BitStuffing::kExact);
// The same contract as can_crc15, one bit at a time.
uint16_t can_crc15_reference(const uint8_t* bits_msb_first, unsigned bit_count);

}  // namespace a3::bridge
