// uavcan.equipment.power.BatteryInfo.
#pragma once

#include <cstdint>

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

struct BatteryInfo {
  static constexpr DataTypeInfo kType{"uavcan.equipment.power.BatteryInfo", 1092,
                                      0x249c26548a711966ULL, 437};
  static constexpr uint16_t kFlagInUse = 1, kFlagCharging = 2, kFlagCharged = 4,
                            kFlagTempHot = 8, kFlagTempCold = 16, kFlagOverload = 32,
                            kFlagBadBattery = 64, kFlagNeedService = 128, kFlagBmsError = 256;
  static constexpr uint8_t kStateOfHealthUnknown = 127, kStateOfChargeUnknown = 127;
  float temperature = 0;              // K, float16 (all float16 below)
  float voltage = 0;                  // V
  float current = 0;                  // A
  float average_power_10sec = 0;      // W
  float remaining_capacity_wh = 0;    // Wh
  float full_charge_capacity_wh = 0;  // Wh
  float hours_to_full_charge = 0;     // h
  uint16_t status_flags = 0;          // uint11
  uint8_t state_of_health_pct = 0;    // uint7
  uint8_t state_of_charge_pct = 0;    // uint7
  uint8_t state_of_charge_pct_stdev = 0;  // uint7
  uint8_t battery_id = 0;
  uint32_t model_instance_id = 0;
  BoundedVector<uint8_t, 31> model_name;  // text (text_array / array_text)

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.temperature, "temperature", dsdl::Float{16});
    v(self.voltage, "voltage", dsdl::Float{16});
    v(self.current, "current", dsdl::Float{16});
    v(self.average_power_10sec, "average_power_10sec", dsdl::Float{16});
    v(self.remaining_capacity_wh, "remaining_capacity_wh", dsdl::Float{16});
    v(self.full_charge_capacity_wh, "full_charge_capacity_wh", dsdl::Float{16});
    v(self.hours_to_full_charge, "hours_to_full_charge", dsdl::Float{16});
    v(self.status_flags, "status_flags", dsdl::Uint{11});
    v(self.state_of_health_pct, "state_of_health_pct", dsdl::Uint{7});
    v(self.state_of_charge_pct, "state_of_charge_pct", dsdl::Uint{7});
    v(self.state_of_charge_pct_stdev, "state_of_charge_pct_stdev", dsdl::Uint{7});
    v(self.battery_id, "battery_id", dsdl::Uint{8});
    v(self.model_instance_id, "model_instance_id", dsdl::Uint{32});
    v(self.model_name, "model_name", dsdl::Array{dsdl::Uint{8}, true});
  }
  bool operator==(const BatteryInfo&) const = default;
};

}  // namespace a3::bridge
