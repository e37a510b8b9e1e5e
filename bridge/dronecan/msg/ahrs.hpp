// uavcan.equipment.ahrs.RawIMU and uavcan.equipment.ahrs.MagneticFieldStrength2.
// Body frame as DroneCAN defines it: X forward, Y right, Z down.
#pragma once

#include <array>
#include <cstdint>

#include "bridge/dronecan/dsdl_types.hpp"
#include "bridge/dronecan/msg/protocol.hpp"

namespace a3::bridge {

struct AhrsRawImu {
  static constexpr DataTypeInfo kType{"uavcan.equipment.ahrs.RawIMU", 1003, 0x8280632c40e574b5ULL,
                                      958};
  Timestamp timestamp;
  float integration_interval = 0;              // s, float32; <= 0: no integrated samples
  std::array<float, 3> rate_gyro_latest{};     // rad/s, float16
  std::array<float, 3> rate_gyro_integral{};   // rad, float32
  std::array<float, 3> accelerometer_latest{};    // m/s^2, float16
  std::array<float, 3> accelerometer_integral{};  // m/s, float32
  BoundedVector<float, 36> covariance;            // float16

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.timestamp, "timestamp", dsdl::Compound{});
    v(self.integration_interval, "integration_interval", dsdl::Float{32});
    v(self.rate_gyro_latest, "rate_gyro_latest", dsdl::Array{dsdl::Float{16}});
    v(self.rate_gyro_integral, "rate_gyro_integral", dsdl::Array{dsdl::Float{32}});
    v(self.accelerometer_latest, "accelerometer_latest", dsdl::Array{dsdl::Float{16}});
    v(self.accelerometer_integral, "accelerometer_integral", dsdl::Array{dsdl::Float{32}});
    v(self.covariance, "covariance", dsdl::Array{dsdl::Float{16}});
  }
  bool operator==(const AhrsRawImu&) const = default;
};

struct MagneticFieldStrength2 {
  static constexpr DataTypeInfo kType{"uavcan.equipment.ahrs.MagneticFieldStrength2", 1002,
                                      0xb6ac0c442430297eULL, 204};
  uint8_t sensor_id = 0;
  std::array<float, 3> magnetic_field_ga{};        // gauss, float16
  BoundedVector<float, 9> magnetic_field_covariance;  // float16

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.sensor_id, "sensor_id", dsdl::Uint{8});
    v(self.magnetic_field_ga, "magnetic_field_ga", dsdl::Array{dsdl::Float{16}});
    v(self.magnetic_field_covariance, "magnetic_field_covariance", dsdl::Array{dsdl::Float{16}});
  }
  bool operator==(const MagneticFieldStrength2&) const = default;
};

}  // namespace a3::bridge
