// uavcan.equipment.gnss.Fix2 and its nested ECEFPositionVelocity.
#pragma once

#include <array>
#include <cstdint>

#include "bridge/dronecan/dsdl_types.hpp"
#include "bridge/dronecan/msg/protocol.hpp"

namespace a3::bridge {

struct GnssEcefPositionVelocity {
  static constexpr DataTypeInfo kType{"uavcan.equipment.gnss.ECEFPositionVelocity", 0,
                                      0x24a5da4abee3a248ULL, 792};
  std::array<float, 3> velocity_xyz{};       // m/s, float32
  std::array<int64_t, 3> position_xyz_mm{};  // int36
  BoundedVector<float, 36> covariance;       // float16

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.velocity_xyz, "velocity_xyz", dsdl::Array{dsdl::Float{32}});
    v(self.position_xyz_mm, "position_xyz_mm", dsdl::Array{dsdl::Int{36}});
    v.void_field(6);
    v(self.covariance, "covariance", dsdl::Array{dsdl::Float{16}});
  }
  bool operator==(const GnssEcefPositionVelocity&) const = default;
};

struct GnssFix2 {
  static constexpr DataTypeInfo kType{"uavcan.equipment.gnss.Fix2", 1063, 0xca41e7000f37435fULL,
                                      1769};
  static constexpr uint8_t kTimeStandardNone = 0, kTimeStandardTai = 1, kTimeStandardUtc = 2,
                           kTimeStandardGps = 3;
  static constexpr uint8_t kStatusNoFix = 0, kStatusTimeOnly = 1, kStatus2dFix = 2,
                           kStatus3dFix = 3;
  static constexpr uint8_t kModeSingle = 0, kModeDgps = 1, kModeRtk = 2, kModePpp = 3;
  Timestamp timestamp;
  Timestamp gnss_timestamp;
  uint8_t gnss_time_standard = 0;  // uint3
  uint8_t num_leap_seconds = 0;
  int64_t longitude_deg_1e8 = 0;   // int37
  int64_t latitude_deg_1e8 = 0;    // int37
  int32_t height_ellipsoid_mm = 0;  // int27
  int32_t height_msl_mm = 0;        // int27
  std::array<float, 3> ned_velocity{};  // m/s, float32, north-east-down
  uint8_t sats_used = 0;  // uint6
  uint8_t status = 0;     // uint2
  uint8_t mode = 0;       // uint4
  uint8_t sub_mode = 0;   // uint6
  BoundedVector<float, 36> covariance;  // float16
  float pdop = 0;                       // float16
  BoundedVector<GnssEcefPositionVelocity, 1> ecef_position_velocity;

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.timestamp, "timestamp", dsdl::Compound{});
    v(self.gnss_timestamp, "gnss_timestamp", dsdl::Compound{});
    v(self.gnss_time_standard, "gnss_time_standard", dsdl::Uint{3});
    v.void_field(13);
    v(self.num_leap_seconds, "num_leap_seconds", dsdl::Uint{8});
    v(self.longitude_deg_1e8, "longitude_deg_1e8", dsdl::Int{37});
    v(self.latitude_deg_1e8, "latitude_deg_1e8", dsdl::Int{37});
    v(self.height_ellipsoid_mm, "height_ellipsoid_mm", dsdl::Int{27});
    v(self.height_msl_mm, "height_msl_mm", dsdl::Int{27});
    v(self.ned_velocity, "ned_velocity", dsdl::Array{dsdl::Float{32}});
    v(self.sats_used, "sats_used", dsdl::Uint{6});
    v(self.status, "status", dsdl::Uint{2});
    v(self.mode, "mode", dsdl::Uint{4});
    v(self.sub_mode, "sub_mode", dsdl::Uint{6});
    v(self.covariance, "covariance", dsdl::Array{dsdl::Float{16}});
    v(self.pdop, "pdop", dsdl::Float{16});
    v(self.ecef_position_velocity, "ecef_position_velocity", dsdl::Array{dsdl::Compound{}});
  }
  bool operator==(const GnssFix2&) const = default;
};

}  // namespace a3::bridge
