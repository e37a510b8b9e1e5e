// uavcan.equipment.esc.RawCommand and uavcan.equipment.esc.Status.
#pragma once

#include <cstdint>

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

struct EscRawCommand {
  static constexpr DataTypeInfo kType{"uavcan.equipment.esc.RawCommand", 1030,
                                      0x217f5c87d7ec951dULL, 285};
  static constexpr int16_t kMin = -8192, kMax = 8191;
  BoundedVector<int16_t, 20> cmd;  // int14 each, [-8192, 8191]; 0 = stop

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.cmd, "cmd", dsdl::Array{dsdl::Int{14}});
  }
  bool operator==(const EscRawCommand&) const = default;
};

struct EscStatus {
  static constexpr DataTypeInfo kType{"uavcan.equipment.esc.Status", 1034, 0xa9af28aea2fbb254ULL,
                                      110};
  uint32_t error_count = 0;
  float voltage = 0;      // V, float16
  float current = 0;      // A, float16
  float temperature = 0;  // K, float16
  int32_t rpm = 0;        // int18
  uint8_t power_rating_pct = 0;  // uint7
  uint8_t esc_index = 0;         // uint5

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.error_count, "error_count", dsdl::Uint{32});
    v(self.voltage, "voltage", dsdl::Float{16});
    v(self.current, "current", dsdl::Float{16});
    v(self.temperature, "temperature", dsdl::Float{16});
    v(self.rpm, "rpm", dsdl::Int{18});
    v(self.power_rating_pct, "power_rating_pct", dsdl::Uint{7});
    v(self.esc_index, "esc_index", dsdl::Uint{5});
  }
  bool operator==(const EscStatus&) const = default;
};

}  // namespace a3::bridge
