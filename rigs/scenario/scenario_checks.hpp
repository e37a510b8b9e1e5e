// The semantic rules a scenario must keep, checked after its schema and parse (the schema
// cannot see geometry or the airframe): home inside the geofence and clear of every no-fly
// zone; every objective's point, area and target inside the geofence and clear of every zone
// at the objective's altitude; objective and cruise altitudes inside the envelope; wind and
// gust within what the airframe can hold against (wind_hold_limit_mps); the payload within
// its lift (hover throttle at most kMaxHoverThrottle).
#pragma once

#include <string>
#include <vector>

#include "dynamics/vehicle_params.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

inline constexpr double kMaxHoverThrottle = 0.85;  // the rest is the control margin
inline constexpr double kWindMargin = 0.8;         // the mean wind may use this share of the limit

// The horizontal airspeed the loaded airframe can hold position against: the body drag at
// that airspeed equals the horizontal thrust at the steepest tilt it can fly (the fc's tilt
// limit, or less when the rotors cannot hold altitude at that tilt).
double wind_hold_limit_mps(const dynamics::VehicleParams& loaded_airframe, double max_tilt_deg);

// One line per problem: "<where>: <JSON path>: <reason>". loaded_airframe: the scenario's
// airframe with its payloads.
std::vector<std::string> scenario_problems(const Scenario& s, const dynamics::VehicleParams& loaded_airframe,
                                           double max_tilt_deg, const std::string& where);

}  // namespace a3::rigs
