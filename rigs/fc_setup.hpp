// How the rig parameterises the flight controller from what it knows of the vehicle and the
// scenario, kept here so that bridge/ never depends on dynamics/: the fc's vehicle section
// (mass with payloads, arm length, rotor constants, inertia) from a dynamics airframe, and
// the geofence and altitude envelope from an α³-Bench initial_state's `airspace`.
// Precedence when the fc node starts: FcParams defaults < airframe (+ payloads) < scenario
// airspace < the parameter file given with --params.
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bridge/fc/fc_params.hpp"
#include "bridge/fc/geo.hpp"
#include "common/json_file.hpp"
#include "dynamics/vehicle_params.hpp"

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

// The geofence of an initial_state: the first polygon of airspace.geofence (ENU metres) and
// airspace.alt_bounds [min, max]. Absent parts stay unbounded. Throws common::InputError
// naming the field.
inline bridge::Geofence geofence_from_initial_state(const nlohmann::json& state, const std::string& where) {
  if (!state.is_object() || !state.contains("airspace")) return {};
  const auto& airspace = common::require_object(state, "airspace", where);
  const std::string wa = where + "/airspace";
  double min_m = -1e9, max_m = 1e9;
  if (airspace.contains("alt_bounds")) {
    const auto& b = common::require_array(airspace, "alt_bounds", wa);
    if (b.size() != 2 || !b[0].is_number() || !b[1].is_number() || !(b[0].get<double>() < b[1].get<double>())) {
      throw common::InputError(wa + "/alt_bounds: expected [min, max] with min < max");
    }
    min_m = b[0].get<double>();
    max_m = b[1].get<double>();
  }
  std::vector<Eigen::Vector2d> polygon;
  if (airspace.contains("geofence")) {
    const auto& fences = common::require_array(airspace, "geofence", wa);
    if (!fences.empty()) {
      const std::string wf = wa + "/geofence/0";
      const auto& points = common::require_array(fences[0], "points", wf);
      for (std::size_t i = 0; i < points.size(); ++i) {
        const auto& p = points[i];
        if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number()) {
          throw common::InputError(wf + "/points/" + std::to_string(i) + ": expected [x, y] in metres");
        }
        polygon.emplace_back(p[0].get<double>(), p[1].get<double>());
      }
      if (polygon.size() < 3) throw common::InputError(wf + "/points: a polygon needs at least 3 points");
    }
  }
  return bridge::Geofence(std::move(polygon), min_m, max_m);
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
