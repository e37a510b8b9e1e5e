// The vehicle's sensors and payloads as the scenario declares them (SensorSuiteConfig, parsed
// from initial_state.uav.sensors and uav.payloads: sensor_suite_config.hpp), which of them are switched on,
// and how large an image each takes. A sensor is usable when its health is one of
// "ok", "nominal", "online", "active", "ready", "standby", "locked" (any case); anything else
// ("offline", "failed", "degraded", ...) makes activate_sensor and capture_image answer an
// error. rgb is on from the start when usable (and usable when the scenario does not list it).
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "vehicle/sensor_suite_config.hpp"

namespace a3::vehicle {

// Image sizes by sensor kind, bytes (a capture's bytes cross the downlink unless stored).
struct ImageSizes {
  std::map<std::string, int64_t> bytes_by_kind = {{"rgb", 3'500'000}, {"thermal", 650'000}, {"lidar", 6'000'000}};
  int64_t default_bytes = 2'000'000;  // any other imaging sensor or payload

  void validate(const std::string& where) const;
};

struct SensorInfo {
  std::string name;
  std::string health;    // as the scenario says ("ok", "offline", ...); "ok" for payloads
  bool usable = false;
  bool payload = false;  // from uav.payloads
  bool imaging = false;  // can capture_image
  std::string kind;      // "rgb", "thermal", "lidar", or the name itself
  double power_w = 0.0;  // payload power_W, when given
};

class SensorSuite {
 public:
  // Throws std::invalid_argument naming the payload ("uav.payloads[0].id: expected a non-empty
  // string", "uav.payloads[1].id: 'rgb' is also a sensor name").
  SensorSuite(const SensorSuiteConfig& declared, ImageSizes sizes);

  const SensorInfo* find(const std::string& name) const;
  std::vector<std::string> names() const;
  bool active(const std::string& name) const { return active_.count(name) != 0; }
  void set_active(const std::string& name, bool on);
  int64_t image_bytes(const SensorInfo& sensor) const;

 private:
  void add_sensor(const std::string& name, const std::string& health);
  void add_payload(const DeclaredPayload& payload, std::size_t index);

  std::map<std::string, SensorInfo> sensors_;
  std::set<std::string> active_;
  ImageSizes sizes_;
};

}  // namespace a3::vehicle
