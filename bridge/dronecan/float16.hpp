// IEEE 754 half precision, as DroneCAN's float16 fields carry it.
#pragma once

#include <cstdint>

namespace a3::bridge {

// Round to nearest, ties to even (libuavcan's and pydronecan's conversion). Values beyond
// the float16 range become infinity here: saturation is the serializer's job. NaN -> 0x7E00.
uint16_t float16_bits_from_float(float value);
float float_from_float16_bits(uint16_t bits);

inline constexpr float kFloat16Max = 65504.0f;

}  // namespace a3::bridge
