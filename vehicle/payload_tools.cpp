// Sensor and network tools: activate_sensor, capture_image (the image's bytes cross the
// downlink with its observation unless stored), switch_network_slice (through the link
// emulator's slice-switch request/reply).
#include <algorithm>
#include <cstdio>

#include "vehicle/observation_json.hpp"
#include "vehicle/vehicle_tools.hpp"

namespace a3::vehicle {
namespace {

std::string names_of(const SensorSuite& sensors) {
  std::string out;
  for (const auto& n : sensors.names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::string unknown_sensor(const SensorSuite& sensors, const std::string& name) {
  return "args/sensor: unknown sensor or payload '" + name + "'; the vehicle has: " + names_of(sensors);
}

void activate_sensor(VehicleServices& vehicle, const nlohmann::json& args) {
  SensorSuite& sensors = vehicle.sensor_suite();
  const std::string name = args.at("sensor").get<std::string>();
  const bool on = args.value("active", true);
  const SensorInfo* sensor = sensors.find(name);
  if (sensor == nullptr) return vehicle.finish_error(unknown_sensor(sensors, name));
  if (on && !sensor->usable) {
    return vehicle.finish_error("args/sensor: " + name + " is " + sensor->health + " and cannot be switched on");
  }
  const bool was_active = sensors.active(name);
  sensors.set_active(name, on);
  if (was_active != on) vehicle.publish_payload_event(on ? "activated" : "deactivated", name, nullptr);
  nlohmann::json result = {{"sensor", name},
                           {"status", on ? "active" : "inactive"},
                           {"was_active", was_active},
                           {"kind", sensor->kind},
                           {"health", sensor->health},
                           {"imaging", sensor->imaging}};
  if (sensor->payload) result["power_W"] = rounded(sensor->power_w, 1);
  vehicle.finish_mcp(result);
}

void capture_image(VehicleServices& vehicle, const nlohmann::json& args) {
  const SensorSuite& sensors = vehicle.sensor_suite();
  const std::string name = args.value("sensor", std::string("rgb"));
  const bool store_only = args.value("store_only", false);
  const SensorInfo* sensor = sensors.find(name);
  if (sensor == nullptr) return vehicle.finish_error(unknown_sensor(sensors, name));
  if (!sensor->imaging) return vehicle.finish_error("args/sensor: " + name + " does not take images");
  if (!sensor->usable) return vehicle.finish_error("args/sensor: " + name + " is " + sensor->health);
  if (!sensors.active(name)) {
    return vehicle.finish_error("args/sensor: " + name + " is not active (call activate_sensor first)");
  }
  const ImageRecord& image = vehicle.capture(*sensor, !store_only);
  const auto& records = vehicle.image_store().records();
  const auto on_board = std::count_if(records.begin(), records.end(), [](const ImageRecord& r) { return !r.downlinked; });
  vehicle.finish_mcp({{"status", "captured"},
                      {"image_id", image.id},
                      {"sensor", name},
                      {"size_bytes", image.size_bytes},
                      {"downlinked", image.downlinked},
                      {"pose", pose_json(image.p_W_m, image.yaw_deg)},
                      {"stored_on_board", static_cast<std::size_t>(on_board)}},
                     image.downlinked ? image.size_bytes : 0);
}

// The observation of a slice switch from the network's reply (nullptr: none in time).
nlohmann::json slice_switch_result(const VehicleServices& vehicle, const std::string& slice,
                                   const a3lcm::slice_switch_reply_t* r) {
  if (r == nullptr) {
    char text[128];
    std::snprintf(text, sizeof text, "no answer from the network within %.1f s", vehicle.config().slice_reply_timeout_s);
    return {{"status", "timeout"}, {"slice", slice}, {"reason", text}};
  }
  if (!r->accepted) return {{"status", "refused"}, {"slice", slice}, {"from_slice", r->from_slice}, {"reason", r->reason}};
  const double effective_in_s = std::max(0.0, static_cast<double>(r->effective_utime_us - vehicle.now_us()) * 1e-6);
  nlohmann::json result = {{"status", r->from_slice == slice ? "active" : "switching"},
                           {"slice", slice},
                           {"from_slice", r->from_slice},
                           {"effective_in_s", rounded(effective_in_s, 3)}};
  if (!r->reason.empty()) result["note"] = r->reason;
  return result;
}

void switch_network_slice(VehicleServices& vehicle, const nlohmann::json& args) {
  const std::string slice = args.at("slice").get<std::string>();
  vehicle.request_slice_switch(slice, [&vehicle, slice](const a3lcm::slice_switch_reply_t* r) {
    vehicle.finish_mcp(slice_switch_result(vehicle, slice, r));
  });
}

}  // namespace

void add_payload_tools(ToolHandlers& handlers) {
  handlers.add_tool("activate_sensor", activate_sensor);
  handlers.add_tool("capture_image", capture_image);
  handlers.add_tool("switch_network_slice", switch_network_slice);
}

}  // namespace a3::vehicle
