// Battery state of charge and voltage.
#include "dynamics/battery.hpp"

#include <algorithm>
#include <cmath>

namespace a3::dynamics {

BatteryReading read_battery(const BatteryParams& b, double capacity_J, double energy_used_J,
                            double power_W) {
  BatteryReading r;
  const double soc = std::clamp(1.0 - energy_used_J / capacity_J, 0.0, 1.0);
  r.percent = 100.0 * soc;
  r.empty = soc <= 0.0;
  const double ocv = b.cells * (b.cell_empty_V + soc * (b.cell_full_V - b.cell_empty_V));
  // P = V·I with V = OCV - I·R: the smaller root of R I² - OCV I + P = 0.
  const double R = b.internal_resistance_ohm;
  const double P = std::max(power_W, 0.0);
  if (R > 0.0) {
    const double disc = ocv * ocv - 4.0 * R * P;
    r.current_A = disc >= 0.0 ? (ocv - std::sqrt(disc)) / (2.0 * R) : ocv / (2.0 * R);
  } else {
    r.current_A = ocv > 0.0 ? P / ocv : 0.0;
  }
  r.voltage_V = ocv - r.current_A * R;
  return r;
}

}  // namespace a3::dynamics
