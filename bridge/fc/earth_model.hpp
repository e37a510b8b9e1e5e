// The Earth as the flight controller and the simulated sensors both see it: the ISA standard
// atmosphere (pressure and temperature against altitude, for the barometer) and the strength of
// the magnetic field (its direction is state_estimator.hpp's earth_field_direction_W).
#pragma once

namespace a3::bridge {

// ISA static pressure (Pa) at a geometric altitude above mean sea level, and its inverse.
double isa_pressure_Pa(double altitude_msl_m);
double isa_altitude_m(double pressure_Pa);
double isa_temperature_K(double altitude_msl_m);
// The magnitude of the Earth's field used (gauss).
inline constexpr double kEarthFieldGauss = 0.48;

}  // namespace a3::bridge
