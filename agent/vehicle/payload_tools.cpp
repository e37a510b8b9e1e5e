// Sensor and network tools: activate_sensor, capture_image (the image's bytes cross the
// downlink with its observation unless stored), switch_network_slice (through the link
// emulator's slice-switch request/reply).
#include <cmath>
#include <cstdio>

#include "a3lcm/payload_event_t.hpp"
#include "a3lcm/slice_switch_request_t.hpp"
#include "agent/vehicle/observation_json.hpp"
#include "agent/vehicle/tool_server_node.hpp"
#include "common/channels.hpp"

namespace a3::agent {
namespace {

std::string names_of(const SensorSuite& sensors) {
  std::string out;
  for (const auto& n : sensors.names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

double yaw_of(const double q[4]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z)) * 180.0 / M_PI;
}

}  // namespace

void ToolServerNode::true_pose(Eigen::Vector3d* p, double* yaw_deg) const {
  if (true_state_) {
    *p = Eigen::Vector3d(true_state_->p_W_m[0], true_state_->p_W_m[1], true_state_->p_W_m[2]);
    *yaw_deg = yaw_of(true_state_->q_WB);
  } else if (fc_status_) {  // no true state seen yet (the dynamics are not running): the estimate
    *p = *position();
    *yaw_deg = fc_status_->yaw_deg;
  } else {
    *p = config_.home_W_m;
    *yaw_deg = 0.0;
  }
}

void ToolServerNode::publish_payload_event(const std::string& kind, const std::string& sensor,
                                           const ImageRecord* image) {
  a3lcm::payload_event_t e{};
  e.utime_us = executor_->clock().now_us();
  e.kind = kind;
  e.sensor = sensor;
  Eigen::Vector3d p;
  double yaw = 0.0;
  if (image != nullptr) {
    p = image->p_W_m;
    yaw = image->yaw_deg;
    e.item_id = image->id;
    e.size_bytes = image->size_bytes;
    e.downlinked = image->downlinked;
  } else {
    true_pose(&p, &yaw);
  }
  for (int k = 0; k < 3; ++k) e.p_W_m[k] = p[k];
  e.yaw_deg = yaw;
  bus_->publish(common::channels::kPayload, e);
}

const ImageRecord& ToolServerNode::capture(const SensorInfo& sensor, bool downlink) {
  Eigen::Vector3d p;
  double yaw = 0.0;
  true_pose(&p, &yaw);
  const ImageRecord& image =
      images_.add(sensor.name, sensors_.image_bytes(sensor), p, yaw, executor_->clock().now_us(), downlink);
  ++counters_->images_captured;
  if (downlink) counters_->image_bytes_downlinked += static_cast<uint64_t>(image.size_bytes);
  publish_payload_event("capture", sensor.name, &image);
  return image;
}

void ToolServerNode::tool_activate_sensor(const nlohmann::json& args) {
  const std::string name = args.at("sensor").get<std::string>();
  const bool on = args.value("active", true);
  const SensorInfo* sensor = sensors_.find(name);
  if (sensor == nullptr) {
    return finish_error("args/sensor: unknown sensor or payload '" + name + "'; the vehicle has: " + names_of(sensors_));
  }
  if (on && !sensor->usable) {
    return finish_error("args/sensor: " + name + " is " + sensor->health + " and cannot be switched on");
  }
  const bool was_active = sensors_.active(name);
  sensors_.set_active(name, on);
  if (was_active != on) publish_payload_event(on ? "activated" : "deactivated", name, nullptr);
  nlohmann::json result = {{"sensor", name},
                           {"status", on ? "active" : "inactive"},
                           {"was_active", was_active},
                           {"kind", sensor->kind},
                           {"health", sensor->health},
                           {"imaging", sensor->imaging}};
  if (sensor->payload) result["power_W"] = rounded(sensor->power_w, 1);
  finish_mcp(result);
}

void ToolServerNode::tool_capture_image(const nlohmann::json& args) {
  const std::string name = args.value("sensor", std::string("rgb"));
  const bool store_only = args.value("store_only", false);
  const SensorInfo* sensor = sensors_.find(name);
  if (sensor == nullptr) {
    return finish_error("args/sensor: unknown sensor or payload '" + name + "'; the vehicle has: " + names_of(sensors_));
  }
  if (!sensor->imaging) return finish_error("args/sensor: " + name + " does not take images");
  if (!sensor->usable) return finish_error("args/sensor: " + name + " is " + sensor->health);
  if (!sensors_.active(name)) return finish_error("args/sensor: " + name + " is not active (call activate_sensor first)");
  const ImageRecord& image = capture(*sensor, !store_only);
  std::size_t on_board = 0;
  for (const auto& r : images_.records()) on_board += r.downlinked ? 0 : 1;
  finish_mcp({{"status", "captured"},
              {"image_id", image.id},
              {"sensor", name},
              {"size_bytes", image.size_bytes},
              {"downlinked", image.downlinked},
              {"pose", pose_json(image.p_W_m, image.yaw_deg)},
              {"stored_on_board", on_board}},
             image.downlinked ? image.size_bytes : 0);
}

void ToolServerNode::tool_switch_network_slice(const nlohmann::json& args) {
  const std::string slice = args.at("slice").get<std::string>();
  a3lcm::slice_switch_request_t request{};
  request.utime_us = executor_->clock().now_us();
  request.request_id = next_slice_request_++;
  request.requester = config_.sender;
  request.slice = slice;
  bus_->publish(common::channels::kSliceRequest, request);
  await_slice_reply(request.request_id, [this, slice](const a3lcm::slice_switch_reply_t* r) {
    if (r == nullptr) {
      char text[128];
      std::snprintf(text, sizeof text, "no answer from the network within %.1f s", config_.slice_reply_timeout_s);
      return finish_mcp({{"status", "timeout"}, {"slice", slice}, {"reason", text}});
    }
    if (!r->accepted) {
      return finish_mcp({{"status", "refused"}, {"slice", slice}, {"from_slice", r->from_slice}, {"reason", r->reason}});
    }
    const double effective_in_s =
        std::max(0.0, static_cast<double>(r->effective_utime_us - executor_->clock().now_us()) * 1e-6);
    nlohmann::json result = {{"status", r->from_slice == slice ? "active" : "switching"},
                             {"slice", slice},
                             {"from_slice", r->from_slice},
                             {"effective_in_s", rounded(effective_in_s, 3)}};
    if (!r->reason.empty()) result["note"] = r->reason;
    finish_mcp(result);
  });
}

}  // namespace a3::agent
