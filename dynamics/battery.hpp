// The battery as the vehicle state reports it: state of charge from the energy drawn, and the
// terminal voltage of a LiPo pack (open-circuit voltage, linear in the state of charge between
// the empty and full cell voltages, minus the internal-resistance drop at the drawn power).
#pragma once

#include "dynamics/vehicle_params.hpp"

namespace a3::dynamics {

struct BatteryReading {
  double percent = 100.0;  // state of charge, [0, 100]
  double voltage_V = 0.0;  // terminal voltage
  double current_A = 0.0;
  bool empty = false;
};

// capacity_J: usable energy (capacity_Ah · cells · nominal V).
BatteryReading read_battery(const BatteryParams& battery, double capacity_J, double energy_used_J,
                            double power_W);

}  // namespace a3::dynamics
