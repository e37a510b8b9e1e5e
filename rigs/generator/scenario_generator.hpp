// Procedurally generated missions: from a seed and the knobs of scenario_generator_knobs.hpp to
// a scenario document in the format of rigs/scenarios/*.json, valid by construction and then
// checked as a file is.
//
// By construction: home and every objective point and area lie inside the geofence with a
// margin and clear of every no-fly zone; zones sit across the first leg and the way home, never
// across a leg between two objectives; the objective steps fit the turn budget. Then checked
// with the rig's own numbers (scenario_generator_check.hpp): the document loads through
// scenario_from_json, the payload is within the airframe's lift, the wind within what it can
// fly at its tilt limit, the ground station's planner finds the way out and the way home
// around the zones, the safety gate passes every leg between objectives and the battery
// estimate of the whole mission keeps the reserve, and the time limit covers the route at the
// ground speed into the wind with margin. A layout that fails is drawn again (the attempt is
// part of the seed's streams, so the result stays a function of seed and knobs); when 64
// draws fail the knobs ask for the impossible and common::InputError says why.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

#include "rigs/generator/scenario_generator_knobs.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

// The scenario document (deterministic: the same seed and knobs give the same document).
nlohmann::json generate_scenario_json(const GeneratorSpec& spec);
// The document loaded through scenario_from_json; source and name carry the spec.
Scenario generate_scenario(const std::string& spec);

}  // namespace a3::rigs
