// The ISA standard atmosphere below the tropopause.
#include "bridge/fc/earth_model.hpp"

#include <cmath>

namespace a3::bridge {
namespace {

constexpr double kSeaLevelPressure_Pa = 101325.0;
constexpr double kSeaLevelTemperature_K = 288.15;
constexpr double kLapseRate_Kpm = 0.0065;
constexpr double kExponent = 5.25588;  // g M / (R L)

}  // namespace

double isa_pressure_Pa(double h) {
  return kSeaLevelPressure_Pa * std::pow(1.0 - kLapseRate_Kpm * h / kSeaLevelTemperature_K, kExponent);
}

double isa_altitude_m(double p) {
  return kSeaLevelTemperature_K / kLapseRate_Kpm * (1.0 - std::pow(p / kSeaLevelPressure_Pa, 1.0 / kExponent));
}

double isa_temperature_K(double h) { return kSeaLevelTemperature_K - kLapseRate_Kpm * h; }

}  // namespace a3::bridge
