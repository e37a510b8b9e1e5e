// uav.sensors → sensor health by name.
#include "vehicle/sensor_suite_config.hpp"

#include "common/json_file.hpp"

namespace a3::vehicle {

std::map<std::string, std::string> parse_sensor_health(const nlohmann::json& sensors, std::string_view json_path) {
  const std::string w(json_path);
  if (!sensors.is_object()) {
    throw common::InputError(w + ": expected an object, got " + std::string(sensors.type_name()));
  }
  std::map<std::string, std::string> out;
  for (const auto& [name, health] : sensors.items()) {
    if (!health.is_string()) {
      throw common::InputError(w + "/" + name + ": expected a health string (\"ok\", \"offline\", ...)");
    }
    out[name] = health.get<std::string>();
  }
  return out;
}

}  // namespace a3::vehicle
