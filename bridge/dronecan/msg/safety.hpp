// uavcan.equipment.safety.ArmingStatus.
#pragma once

#include <cstdint>

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

struct ArmingStatus {
  static constexpr DataTypeInfo kType{"uavcan.equipment.safety.ArmingStatus", 1100,
                                      0x8700f375556a8003ULL, 8};
  static constexpr uint8_t kDisarmed = 0, kFullyArmed = 255;
  uint8_t status = 0;

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.status, "status", dsdl::Uint{8});
  }
  bool operator==(const ArmingStatus&) const = default;
};

}  // namespace a3::bridge
