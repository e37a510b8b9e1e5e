// What the sensor suite is configured from: the scenario's initial_state.uav.sensors (name →
// health, parsed here by parse_sensor_health) and what uav.payloads declares about each payload
// (DeclaredPayload: filled by the scenario's payload parser, rigs/scenario/uav_payloads.hpp, which
// also reads the payloads' physical part for the dynamics).
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace a3::vehicle {

struct DeclaredPayload {
  std::string id;        // non-empty (the scenario's parser names an id-less payload by its index)
  std::string type;      // e.g. "gimbaled_camera", "" when not given
  std::string category;  // e.g. "imaging_thermal", "" when not given
  double power_W = 0.0;
};

struct SensorSuiteConfig {
  std::map<std::string, std::string> sensor_health;  // uav.sensors: name → health ("ok", "offline", ...)
  std::vector<DeclaredPayload> payloads;             // uav.payloads, in order
};

// Parses uav.sensors: an object of health strings. `json_path` names where it is
// ("file.json: /initial_state/uav/sensors"); throws common::InputError naming the path and name.
std::map<std::string, std::string> parse_sensor_health(const nlohmann::json& sensors, std::string_view json_path);

}  // namespace a3::vehicle
