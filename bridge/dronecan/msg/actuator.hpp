// uavcan.equipment.actuator.ArrayCommand and its nested Command.
#pragma once

#include <cstdint>

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

struct ActuatorCommand {
  static constexpr DataTypeInfo kType{"uavcan.equipment.actuator.Command", 0,
                                      0x8d9a6a920c1d616cULL, 32};
  static constexpr uint8_t kTypeUnitless = 0, kTypePosition = 1, kTypeForce = 2,
                           kTypeSpeed = 3, kTypePwm = 4;
  uint8_t actuator_id = 0;
  uint8_t command_type = 0;
  float command_value = 0;  // float16, unit per command_type

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.actuator_id, "actuator_id", dsdl::Uint{8});
    v(self.command_type, "command_type", dsdl::Uint{8});
    v(self.command_value, "command_value", dsdl::Float{16});
  }
  bool operator==(const ActuatorCommand&) const = default;
};

struct ActuatorArrayCommand {
  static constexpr DataTypeInfo kType{"uavcan.equipment.actuator.ArrayCommand", 1010,
                                      0xd8a7486238ec3af3ULL, 484};
  BoundedVector<ActuatorCommand, 15> commands;

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.commands, "commands", dsdl::Array{dsdl::Compound{}});
  }
  bool operator==(const ActuatorArrayCommand&) const = default;
};

}  // namespace a3::bridge
