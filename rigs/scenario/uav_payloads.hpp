// The one parser of initial_state.uav.payloads (the α³-Bench corpus format: objects with id,
// type, category, mass_kg, drag_cdA, power_W, and fields a3rig does not read). Each payload
// is read once into what each component needs: the physical part for the dynamics
// (dynamics::Payload) and the declared part for the tool server's sensor suite
// (vehicle::DeclaredPayload).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "dynamics/vehicle_params.hpp"
#include "vehicle/sensor_suite_config.hpp"

namespace a3::rigs {

struct UavPayloads {
  // Both parts carry the same id: the payload's own, or "payload<i>" (its index) when it has none,
  // as a third of the corpus' payloads do.
  std::vector<dynamics::Payload> physical;       // mass, drag area, power
  std::vector<vehicle::DeclaredPayload> declared;  // id, type, category, power
};

// `json_path` names the array ("file.json: /initial_state/uav/payloads"). mass_kg, drag_cdA
// and power_W default to 0 and must be numbers >= 0; id, type and category, when given,
// strings. Throws common::InputError naming the path of the bad field
// (".../uav/payloads/0/mass_kg: must be >= 0, got -2.000000").
UavPayloads parse_uav_payloads(const nlohmann::json& payloads, const std::string& json_path);

}  // namespace a3::rigs
