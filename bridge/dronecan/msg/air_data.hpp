// uavcan.equipment.air_data.StaticPressure and StaticTemperature.
#pragma once

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

struct StaticPressure {
  static constexpr DataTypeInfo kType{"uavcan.equipment.air_data.StaticPressure", 1028,
                                      0xcdc7c43412bdc89aULL, 48};
  float static_pressure = 0;           // Pa, float32
  float static_pressure_variance = 0;  // Pa^2, float16

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.static_pressure, "static_pressure", dsdl::Float{32});
    v(self.static_pressure_variance, "static_pressure_variance", dsdl::Float{16});
  }
  bool operator==(const StaticPressure&) const = default;
};

struct StaticTemperature {
  static constexpr DataTypeInfo kType{"uavcan.equipment.air_data.StaticTemperature", 1029,
                                      0x49272a6477d96271ULL, 32};
  float static_temperature = 0;           // K, float16
  float static_temperature_variance = 0;  // K^2, float16

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.static_temperature, "static_temperature", dsdl::Float{16});
    v(self.static_temperature_variance, "static_temperature_variance", dsdl::Float{16});
  }
  bool operator==(const StaticTemperature&) const = default;
};

}  // namespace a3::bridge
