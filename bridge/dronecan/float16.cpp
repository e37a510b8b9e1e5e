// float <-> float16 (see float16.hpp); after F. Giesen's float_to_half_fast3_rtne.
#include "bridge/dronecan/float16.hpp"

#include <bit>
#include <cmath>

namespace a3::bridge {

uint16_t float16_bits_from_float(float value) {
  constexpr uint32_t kF32Infinity = 255u << 23;
  constexpr uint32_t kF16MaxPlusOne = (127u + 16u) << 23;
  constexpr uint32_t kDenormMagic = ((127u - 15u) + (23u - 10u) + 1u) << 23;
  uint32_t in = std::bit_cast<uint32_t>(value);
  const uint32_t sign = in & 0x80000000u;
  in ^= sign;
  uint16_t out;
  if (in >= kF16MaxPlusOne) {
    out = in > kF32Infinity ? 0x7E00 : 0x7C00;
  } else if (in < (113u << 23)) {
    // Denormal result: let the FPU round by adding a magic number.
    const float sum = std::bit_cast<float>(in) + std::bit_cast<float>(kDenormMagic);
    out = static_cast<uint16_t>(std::bit_cast<uint32_t>(sum) - kDenormMagic);
  } else {
    const uint32_t mantissa_odd = (in >> 13) & 1u;
    in += (static_cast<uint32_t>(15 - 127) << 23) + 0xFFFu;
    in += mantissa_odd;
    out = static_cast<uint16_t>(in >> 13);
  }
  return static_cast<uint16_t>(out | (sign >> 16));
}

float float_from_float16_bits(uint16_t bits) {
  const uint32_t sign = (static_cast<uint32_t>(bits) & 0x8000u) << 16;
  const uint32_t exponent = (bits >> 10) & 0x1Fu;
  const uint32_t mantissa = bits & 0x3FFu;
  if (exponent == 0) {
    const float magnitude = std::ldexp(static_cast<float>(mantissa), -24);
    return sign != 0 ? -magnitude : magnitude;
  }
  if (exponent == 31) {
    return std::bit_cast<float>(sign | 0x7F800000u | (mantissa << 13));
  }
  return std::bit_cast<float>(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

}  // namespace a3::bridge
