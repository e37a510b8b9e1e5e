// How the rig parameterises the flight controller from what it knows of the vehicle and the
// scenario, kept here so that bridge/ never depends on dynamics/: the fc's vehicle section
// (mass with payloads, arm length, rotor constants, inertia) from a dynamics airframe, and
// the geofence and altitude envelope from the parsed initial_state (rigs/scenario/initial_state.hpp).
// Precedence when the fc node starts: FcParams defaults < airframe (+ payloads) < scenario
// airspace < the parameter file given with --params.
#pragma once

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bridge/fc/fc_params.hpp"
#include "bridge/fc/geo.hpp"
#include "dynamics/vehicle_params.hpp"
#include "rigs/scenario/initial_state.hpp"

namespace a3::rigs {

// What the autopilot is told about its airframe: the same constants the dynamics fly with.
inline bridge::FcVehicle fc_vehicle_from_airframe(const dynamics::VehicleParams& v) {
  bridge::FcVehicle out;
  out.mass_kg = v.total_mass_kg();
  out.arm_length_m = v.arm_length_m;
  out.thrust_coeff_N_per_radps2 = v.rotor.thrust_coeff_N_per_radps2;
  out.torque_coeff_Nm_per_radps2 = v.rotor.drag_torque_coeff_Nm_per_radps2;
  out.max_rotor_speed_radps = v.rotor.max_speed_radps;
  out.inertia_xx_kgm2 = v.inertia_xx_kgm2;
  out.inertia_yy_kgm2 = v.inertia_yy_kgm2;
  out.inertia_zz_kgm2 = v.inertia_zz_kgm2;
  return out;
}

// The fc's fence from the parsed initial_state: the geofence polygon (ENU metres; none:
// unbounded horizontally) and the altitude envelope (airspace.alt_bounds narrowed by
// policy.alt_bounds; none: unbounded).
inline bridge::Geofence geofence_from(const InitialState& state) {
  const AltitudeBounds envelope = state.envelope();
  const double min_m = std::isfinite(envelope.min_m) ? envelope.min_m : -1e9;
  const double max_m = std::isfinite(envelope.max_m) ? envelope.max_m : 1e9;
  return bridge::Geofence(state.geofence, min_m, max_m);
}

// The home point (ENU origin) of the fc and bridge nodes: "LAT,LON,HEIGHT" in degrees and
// metres (WGS-84; the height is also the barometer's reference above sea level). Both nodes
// of a rig must be given the same one. Throws std::invalid_argument saying what is wrong.
inline bridge::Geodetic parse_home(const std::string& text) {
  std::istringstream in(text);
  bridge::Geodetic g;
  char c1 = 0, c2 = 0;
  if (!(in >> g.latitude_deg >> c1 >> g.longitude_deg >> c2 >> g.height_m) || c1 != ',' || c2 != ',' ||
      !(in >> std::ws).eof()) {
    throw std::invalid_argument("home '" + text + "': expected LAT,LON,HEIGHT (degrees, degrees, metres)");
  }
  if (!(std::abs(g.latitude_deg) <= 85.0) || !(std::abs(g.longitude_deg) <= 180.0) ||
      !(std::abs(g.height_m) <= 10000.0)) {
    throw std::invalid_argument("home '" + text + "': latitude within ±85°, longitude ±180°, height ±10 km");
  }
  return g;
}

}  // namespace a3::rigs
