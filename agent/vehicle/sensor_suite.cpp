// Sensors and payloads from the scenario.
#include "agent/vehicle/sensor_suite.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace a3::agent {
namespace {

// Sensors that take no pictures.
const std::set<std::string> kNonImaging = {"gnss", "gps", "imu", "magnetometer", "barometer", "compass"};
const std::set<std::string> kUsableHealth = {"ok", "nominal", "online", "active", "ready", "standby", "locked"};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool contains(const std::string& text, const char* word) { return text.find(word) != std::string::npos; }

// A payload's image kind from its type and category ("imaging_thermal" → thermal).
std::string payload_kind(const std::string& id, const std::string& type, const std::string& category) {
  const std::string t = lower(type + " " + category);
  if (contains(t, "thermal") || contains(t, "lwir")) return "thermal";
  if (contains(t, "lidar")) return "lidar";
  if (contains(t, "optical") || contains(t, "rgb") || contains(t, "camera")) return "rgb";
  return id;
}

bool payload_imaging(const std::string& type, const std::string& category) {
  const std::string t = lower(type + " " + category);
  return contains(t, "imag") || contains(t, "camera") || contains(t, "lidar") || contains(t, "thermal");
}

}  // namespace

void ImageSizes::validate(const std::string& where) const {
  for (const auto& [kind, bytes] : bytes_by_kind) {
    if (bytes <= 0) throw std::invalid_argument(where + ".bytes_by_kind." + kind + " must be > 0, got " + std::to_string(bytes));
  }
  if (default_bytes <= 0) {
    throw std::invalid_argument(where + ".default_bytes must be > 0, got " + std::to_string(default_bytes));
  }
}

SensorSuite::SensorSuite(const nlohmann::json& sensors, const nlohmann::json& payloads, ImageSizes sizes)
    : sizes_(std::move(sizes)) {
  if (!sensors.is_null() && !sensors.is_object()) throw std::invalid_argument("uav.sensors: expected an object");
  if (!payloads.is_null() && !payloads.is_array()) throw std::invalid_argument("uav.payloads: expected an array");
  if (sensors.is_object()) {
    for (const auto& [name, health] : sensors.items()) {
      if (!health.is_string()) throw std::invalid_argument("uav.sensors." + name + ": expected a string");
      SensorInfo s;
      s.name = name;
      s.health = health.get<std::string>();
      s.usable = kUsableHealth.count(lower(s.health)) != 0;
      s.imaging = kNonImaging.count(lower(name)) == 0;
      s.kind = lower(name);
      sensors_[name] = s;
    }
  }
  if (payloads.is_array()) {
    for (std::size_t i = 0; i < payloads.size(); ++i) {
      const auto& p = payloads[i];
      const std::string where = "uav.payloads[" + std::to_string(i) + "]";
      if (!p.is_object()) throw std::invalid_argument(where + ": expected an object");
      if (!p.contains("id") || !p["id"].is_string() || p["id"].get<std::string>().empty()) {
        throw std::invalid_argument(where + ".id: expected a non-empty string");
      }
      const auto text = [&](const char* key) {
        if (!p.contains(key)) return std::string();
        if (!p[key].is_string()) throw std::invalid_argument(where + "." + key + ": expected a string");
        return p[key].get<std::string>();
      };
      SensorInfo s;
      s.name = p["id"].get<std::string>();
      if (sensors_.count(s.name) != 0) throw std::invalid_argument(where + ".id: '" + s.name + "' is also a sensor name");
      s.health = "ok";
      s.usable = true;
      s.payload = true;
      const std::string type = text("type"), category = text("category");
      s.imaging = payload_imaging(type, category);
      s.kind = payload_kind(s.name, type, category);
      if (p.contains("power_W")) {
        if (!p["power_W"].is_number()) throw std::invalid_argument(where + ".power_W: expected a number");
        s.power_w = p["power_W"].get<double>();
      }
      sensors_[s.name] = s;
    }
  }
  if (sensors_.count("rgb") == 0) sensors_["rgb"] = SensorInfo{"rgb", "ok", true, false, true, "rgb", 0.0};
  if (sensors_.at("rgb").usable) active_.insert("rgb");
}

const SensorInfo* SensorSuite::find(const std::string& name) const {
  const auto it = sensors_.find(name);
  return it == sensors_.end() ? nullptr : &it->second;
}

std::vector<std::string> SensorSuite::names() const {
  std::vector<std::string> out;
  for (const auto& [name, info] : sensors_) out.push_back(name);
  return out;
}

void SensorSuite::set_active(const std::string& name, bool on) {
  if (on) {
    active_.insert(name);
  } else {
    active_.erase(name);
  }
}

int64_t SensorSuite::image_bytes(const SensorInfo& sensor) const {
  const auto it = sizes_.bytes_by_kind.find(sensor.kind);
  return it == sizes_.bytes_by_kind.end() ? sizes_.default_bytes : it->second;
}

}  // namespace a3::agent
