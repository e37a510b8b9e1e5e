// Sensors and payloads from the scenario.
#include "vehicle/sensor_suite.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <utility>

namespace a3::vehicle {
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

SensorSuite::SensorSuite(const SensorSuiteConfig& declared, ImageSizes sizes) : sizes_(std::move(sizes)) {
  for (const auto& [name, health] : declared.sensor_health) add_sensor(name, health);
  for (std::size_t i = 0; i < declared.payloads.size(); ++i) add_payload(declared.payloads[i], i);
  if (sensors_.count("rgb") == 0) sensors_["rgb"] = SensorInfo{"rgb", "ok", true, false, true, "rgb", 0.0};
  if (sensors_.at("rgb").usable) active_.insert("rgb");
}

void SensorSuite::add_sensor(const std::string& name, const std::string& health) {
  SensorInfo s;
  s.name = name;
  s.health = health;
  s.usable = kUsableHealth.count(lower(health)) != 0;
  s.imaging = kNonImaging.count(lower(name)) == 0;
  s.kind = lower(name);
  sensors_[name] = s;
}

void SensorSuite::add_payload(const DeclaredPayload& payload, std::size_t index) {
  const std::string where = "uav.payloads[" + std::to_string(index) + "]";
  if (payload.id.empty()) throw std::invalid_argument(where + ".id: expected a non-empty string");
  if (sensors_.count(payload.id) != 0) {
    throw std::invalid_argument(where + ".id: '" + payload.id + "' is also a sensor name");
  }
  SensorInfo s;
  s.name = payload.id;
  s.health = "ok";
  s.usable = true;
  s.payload = true;
  s.imaging = payload_imaging(payload.type, payload.category);
  s.kind = payload_kind(payload.id, payload.type, payload.category);
  s.power_w = payload.power_W;
  sensors_[s.name] = s;
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

}  // namespace a3::vehicle
