// The tool server's side of VehicleServices: fc commands and the wait for their status, onboard
// routes and their sequencing on the fc's status, slice-switch requests, payload events and
// image captures, the clock.
#include <cmath>
#include <limits>

#include "a3lcm/payload_event_t.hpp"
#include "a3lcm/slice_switch_request_t.hpp"
#include "common/channels.hpp"
#include "common/log.hpp"
#include "vehicle/observation_json.hpp"
#include "vehicle/tool_server_node.hpp"

namespace a3::vehicle {
namespace {

constexpr const char* kLog = "tool_server";

int64_t seconds_to_us(double s) { return static_cast<int64_t>(std::llround(s * 1e6)); }

double yaw_of(const double q[4]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z)) * 180.0 / M_PI;
}

}  // namespace

double ToolServerNode::now_s() const { return executor_->clock().now_s(); }

int64_t ToolServerNode::now_us() const { return executor_->clock().now_us(); }

// ---------------------------------------------------------------------------------------------
// The fc and onboard routes

int32_t ToolServerNode::send_fc(int8_t command, const Eigen::Vector3d& target, double speed_mps, double yaw_deg) {
  a3lcm::fc_command_t c{};
  c.utime_us = executor_->clock().now_us();
  c.seq = ++seq_;
  c.command = command;
  for (int k = 0; k < 3; ++k) c.target_W_m[k] = target[k];
  c.speed_limit_mps = speed_mps;
  c.yaw_deg = yaw_deg;
  bus_->publish(common::channels::kFcCommand.of(config_.vehicle), c);
  ++counters_->fc_commands;
  return c.seq;
}

void ToolServerNode::await_status(int32_t seq, StatusContinuation then) {
  awaited_seq_ = seq;
  status_then_ = std::move(then);
  status_timer_ = executor_->schedule_after(seconds_to_us(config_.fc_status_timeout_s), [this] {
    if (!status_then_) return;
    ++counters_->timeouts;
    auto then = std::move(status_then_);
    status_then_ = nullptr;
    then(nullptr);
  });
}

int32_t ToolServerNode::begin_route(OnboardRoute route) {
  cancel_route("superseded by " + route.name());
  route_.emplace(std::move(route));
  ++counters_->routes_started;
  const RoutePoint& first = route_->current();
  const int32_t seq = send_fc(a3lcm::fc_command_t::GOTO, first.p_W_m, route_->speed_mps(), first.yaw_deg);
  route_->leg_sent(seq);
  return seq;
}

void ToolServerNode::cancel_route(const std::string& why) {
  if (!route_) return;
  ++counters_->routes_aborted;
  common::log_info(kLog, "route " + route_->name() + " cancelled at waypoint " + std::to_string(route_->index() + 1) +
                             " of " + std::to_string(route_->points().size()) + ": " + why);
  route_.reset();
}

void ToolServerNode::advance_route(const a3lcm::fc_status_t& s) {
  const auto update = route_->on_status(s, config_.route.arrive_tolerance_m);
  if (update.event == OnboardRoute::Event::kNone) return;
  if (update.event == OnboardRoute::Event::kAborted) {
    cancel_route(update.reason);
    return;
  }
  const RoutePoint& reached = route_->current();
  if (reached.capture) {
    const SensorInfo* sensor = sensors_.find(route_->capture_sensor());
    if (sensor != nullptr && sensor->usable && sensors_.active(sensor->name)) {
      capture(*sensor, false);
    } else {
      common::log_warn(kLog, "route " + route_->name() + ": no capture at waypoint " +
                                 std::to_string(route_->index() + 1) + ", sensor " + route_->capture_sensor() +
                                 " is not active");
    }
  }
  if (route_->advance()) {
    const RoutePoint& next = route_->current();
    route_->leg_sent(send_fc(a3lcm::fc_command_t::GOTO, next.p_W_m, route_->speed_mps(), next.yaw_deg));
    return;
  }
  ++counters_->routes_completed;
  common::log_info(kLog, "route " + route_->name() + " completed (" + std::to_string(route_->points().size()) +
                             " waypoints)");
  const bool land = route_->end() == RouteEnd::kLand;
  route_.reset();
  if (land) {
    const Eigen::Vector3d p = position().value_or(Eigen::Vector3d::Zero());
    send_fc(a3lcm::fc_command_t::LAND, p, 0.0, std::numeric_limits<double>::quiet_NaN());
  }
}

std::optional<Eigen::Vector3d> ToolServerNode::position() const {
  if (!fc_status_) return std::nullopt;
  return Eigen::Vector3d(fc_status_->p_W_m[0], fc_status_->p_W_m[1], fc_status_->p_W_m[2]);
}

nlohmann::json ToolServerNode::pose_now() const {
  if (!fc_status_) return nullptr;
  return pose_json(*position(), fc_status_->yaw_deg);
}

// ---------------------------------------------------------------------------------------------
// The network

void ToolServerNode::request_slice_switch(const std::string& slice, SliceContinuation then) {
  a3lcm::slice_switch_request_t request{};
  request.utime_us = executor_->clock().now_us();
  request.request_id = next_slice_request_++;
  request.requester = config_.sender;
  request.slice = slice;
  bus_->publish(common::channels::kSliceRequest.of(config_.vehicle), request);
  awaited_slice_request_ = request.request_id;
  slice_then_ = std::move(then);
  slice_timer_ = executor_->schedule_after(seconds_to_us(config_.slice_reply_timeout_s), [this] {
    if (!slice_then_) return;
    ++counters_->timeouts;
    auto then = std::move(slice_then_);
    slice_then_ = nullptr;
    then(nullptr);
  });
}

// ---------------------------------------------------------------------------------------------
// Payloads and images

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
  bus_->publish(common::channels::kPayload.of(config_.vehicle), e);
}

const ImageRecord& ToolServerNode::capture(const SensorInfo& sensor, bool downlink) {
  Eigen::Vector3d p;
  double yaw = 0.0;
  true_pose(&p, &yaw);
  const ImageRecord& image =
      images_.add(sensor.name, sensors_.image_bytes(sensor), p, yaw, executor_->clock().now_us(), downlink);
  ++counters_->images_captured;
  if (downlink) count_image_bytes_downlinked(image.size_bytes);
  publish_payload_event("capture", sensor.name, &image);
  return image;
}

void ToolServerNode::count_image_bytes_downlinked(int64_t bytes) {
  counters_->image_bytes_downlinked += static_cast<uint64_t>(bytes);
}

}  // namespace a3::vehicle
