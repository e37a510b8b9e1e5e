// uavcan.Timestamp and uavcan.protocol.NodeStatus (DSDL in ../shared/spec/dronecan/dsdl).
#pragma once

#include <cstdint>

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

struct Timestamp {
  static constexpr DataTypeInfo kType{"uavcan.Timestamp", 0, 0x05bd0b5c81087e0dULL, 56};
  static constexpr uint64_t kUnknown = 0;
  uint64_t usec = 0;  // truncated uint56, microseconds

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.usec, "usec", dsdl::Uint{56, dsdl::Cast::kTruncated});
  }
  bool operator==(const Timestamp&) const = default;
};

struct NodeStatus {
  static constexpr DataTypeInfo kType{"uavcan.protocol.NodeStatus", 341, 0x0f0868d0c1a7c6f1ULL,
                                      56};
  static constexpr uint8_t kHealthOk = 0, kHealthWarning = 1, kHealthError = 2,
                           kHealthCritical = 3;
  static constexpr uint8_t kModeOperational = 0, kModeInitialization = 1, kModeMaintenance = 2,
                           kModeSoftwareUpdate = 3, kModeOffline = 7;
  uint32_t uptime_sec = 0;
  uint8_t health = 0;    // uint2
  uint8_t mode = 0;      // uint3
  uint8_t sub_mode = 0;  // uint3
  uint16_t vendor_specific_status_code = 0;

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.uptime_sec, "uptime_sec", dsdl::Uint{32});
    v(self.health, "health", dsdl::Uint{2});
    v(self.mode, "mode", dsdl::Uint{3});
    v(self.sub_mode, "sub_mode", dsdl::Uint{3});
    v(self.vendor_specific_status_code, "vendor_specific_status_code", dsdl::Uint{16});
  }
  bool operator==(const NodeStatus&) const = default;
};

}  // namespace a3::bridge
