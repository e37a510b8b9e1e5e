// Setting up the dynamics from an α³-Bench `initial_state` (a scenario, or the initial_state of
// any corpus episode): wind (`env.wind_mps`, `env.wind_dir_deg`), payloads (`uav.payloads[]`:
// mass_kg, drag_cdA, power_W) and the start pose (`uav.pose`: x, y, z, yaw in degrees from
// east, ENU).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "dynamics/dynamics_node.hpp"

namespace a3::dynamics {

// The initial_state object of a JSON document: the document itself, or its "initial_state".
const nlohmann::json& initial_state_of(const nlohmann::json& document, const std::string& where);

// Applies wind, payloads and pose to config (params must already hold the airframe). With
// start_on_ground the vehicle starts at z = 0 below the pose; otherwise it starts at the pose,
// rotors at hover speed. Throws common::InputError naming the field.
void apply_initial_state(const nlohmann::json& initial_state, const std::string& where,
                         bool start_on_ground, DynamicsNodeConfig& config);

}  // namespace a3::dynamics
