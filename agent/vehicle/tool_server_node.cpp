// The tool server's inputs, action queue, fc command/status handshake, route sequencing and
// A2A dispatch. The tools themselves are in motion_tools.cpp, query_tools.cpp and
// payload_tools.cpp.
#include "agent/vehicle/tool_server_node.hpp"

#include <cmath>
#include <limits>

#include "a3lcm/safety_event_t.hpp"
#include "a3lcm/slice_switch_request_t.hpp"
#include "agent/vehicle/observation_json.hpp"
#include "common/channels.hpp"
#include "common/log.hpp"

namespace a3::agent {
namespace {

constexpr const char* kLog = "tool_server";

int64_t seconds_to_us(double s) { return static_cast<int64_t>(std::llround(s * 1e6)); }

std::string tool_list(const ToolCatalog& catalog) {
  std::string out;
  for (const auto& t : catalog.tools()) out += (out.empty() ? "" : ", ") + t.name;
  return out;
}

std::string task_list(const ToolCatalog& catalog) {
  std::string out;
  for (const auto& t : catalog.tasks()) out += (out.empty() ? "" : ", ") + t.task;
  return out;
}

}  // namespace

namespace {
const ToolServerConfig& validated(const ToolServerConfig& c) {
  c.validate();
  return c;
}
}  // namespace

ToolServerNode::ToolServerNode(ToolServerConfig config, const ToolCatalog& catalog)
    : config_(validated(config)),
      catalog_(catalog),
      gate_(config_.airspace, config_.gate, config_.energy, config_.home_W_m),
      sensors_(config_.sensors, config_.payloads, config_.images),
      swarm_(config_.airspace.traffic, config_.swarm),
      weather_(config_.env, config_.weather),
      ground_station_(gate_, config_.planner),
      speed_mps_(config_.energy.cruise_speed_mps),
      counters_(std::make_unique<AtomicCounters>(counter_set_)) {}

ToolServerNode::~ToolServerNode() = default;


void ToolServerNode::start(common::Executor& executor, common::Bus& bus) {
  executor_ = &executor;
  bus_ = &bus;
  namespace ch = common::channels;
  bus.subscribe<a3lcm::link_message_t>(ch::kLinkUpRx,
                                       [this](const a3lcm::link_message_t& m, int64_t) { on_link_message(m); });
  bus.subscribe<a3lcm::fc_status_t>(ch::kFcStatus, [this](const a3lcm::fc_status_t& s, int64_t) { on_fc_status(s); });
  bus.subscribe<a3lcm::vehicle_state_t>(ch::kState,
                                        [this](const a3lcm::vehicle_state_t& s, int64_t) { true_state_ = s; });
  bus.subscribe<a3lcm::network_state_t>(ch::kNet, [this](const a3lcm::network_state_t& n, int64_t) { net_ = n; });
  bus.subscribe<a3lcm::slice_switch_reply_t>(
      ch::kSliceReply, [this](const a3lcm::slice_switch_reply_t& r, int64_t) { on_slice_reply(r); });
  if (!swarm_.peers().empty()) {
    executor.schedule_every(seconds_to_us(1.0 / config_.traffic_rate_hz), [this] { publish_traffic(); });
  }
  common::log_info(kLog, "started: " + std::to_string(catalog_.tools().size()) + " tools, " +
                             std::to_string(swarm_.peers().size()) + " peers, " +
                             std::to_string(config_.airspace.no_fly_zones.size()) + " no-fly zones");
}

// ---------------------------------------------------------------------------------------------
// Inputs

void ToolServerNode::on_link_message(const a3lcm::link_message_t& m) {
  ++counters_->link_messages;
  if (m.kind == "heartbeat") {
    a3lcm::fc_command_t c{};
    c.utime_us = executor_->clock().now_us();
    c.seq = seq_;
    c.command = a3lcm::fc_command_t::HEARTBEAT;
    c.yaw_deg = std::numeric_limits<double>::quiet_NaN();
    bus_->publish(common::channels::kFcCommand, c);
    ++counters_->heartbeats_forwarded;
    return;
  }
  if (m.kind == "turn") {  // the dialogue's own turn message: crosses the link, asks nothing
    ++counters_->turn_messages;
    return;
  }
  if (m.kind != "mcp_call" && m.kind != "a2a_message") {
    ++counters_->malformed_dropped;
    common::log_warn(kLog, "dropped link message " + std::to_string(m.message_id) + " from '" + m.sender +
                               "' of unknown kind '" + m.kind + "'");
    return;
  }
  std::string error;
  auto action = decode_action(m, &error);
  if (!action) {
    ++counters_->malformed_dropped;
    common::log_warn(kLog, "dropped malformed link message from '" + m.sender + "': " + error);
    return;
  }
  if (!action->action.contains("type")) action->action["type"] = m.kind == "a2a_message" ? "a2a" : "mcp";
  if (queue_.size() >= config_.max_queued_actions) {
    ++counters_->queue_overflow_dropped;
    common::log_warn(kLog, "dropped action (turn " + std::to_string(action->turn) + ", index " +
                               std::to_string(action->action_index) + "): " +
                               std::to_string(queue_.size()) + " actions already wait");
    return;
  }
  queue_.push_back(std::move(*action));
  process_queue();
}

void ToolServerNode::on_fc_status(const a3lcm::fc_status_t& s) {
  fc_status_ = s;
  if (s.mode != a3lcm::fc_status_t::TAKEOFF) takeoff_target_W_m_.reset();
  if (status_then_ && s.last_command_seq == awaited_seq_) {
    executor_->cancel(status_timer_);
    auto then = std::move(status_then_);
    status_then_ = nullptr;
    if (!s.last_command_accepted) ++counters_->fc_refusals;
    then(&s);
  }
  if (route_) advance_route(s);
}

void ToolServerNode::on_slice_reply(const a3lcm::slice_switch_reply_t& r) {
  if (!slice_then_ || r.request_id != awaited_slice_request_ || r.requester != config_.sender) return;
  executor_->cancel(slice_timer_);
  auto then = std::move(slice_then_);
  slice_then_ = nullptr;
  then(&r);
}

void ToolServerNode::publish_traffic() {
  const int64_t now_us = executor_->clock().now_us();
  for (const auto& m : swarm_.traffic_at(static_cast<double>(now_us) * 1e-6, now_us)) {
    bus_->publish(common::channels::kTraffic, m);
  }
}

// ---------------------------------------------------------------------------------------------
// The action queue

void ToolServerNode::process_queue() {
  if (in_queue_loop_) return;
  in_queue_loop_ = true;
  while (!busy_ && !queue_.empty()) {
    current_ = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    handle(*current_);
  }
  in_queue_loop_ = false;
}

void ToolServerNode::handle(const ActionEnvelope& envelope) {
  const nlohmann::json& action = envelope.action;
  try {
    if (action["type"] == "a2a") {
      ++counters_->a2a_messages;
      handle_a2a(action);
    } else {
      ++counters_->mcp_calls;
      handle_mcp(action);
    }
  } catch (const std::exception& e) {
    common::log_error(kLog, "action (turn " + std::to_string(envelope.turn) + ", index " +
                                std::to_string(envelope.action_index) + ") failed: " + e.what());
    if (busy_ && !status_then_ && !slice_then_) finish_error(std::string("internal error: ") + e.what());
  }
}

void ToolServerNode::handle_mcp(const nlohmann::json& action) {
  if (action["type"] != "mcp") {
    finish_error("action/type: expected \"mcp\" or \"a2a\", got " + action["type"].dump());
    return;
  }
  if (!action.contains("name") || !action["name"].is_string()) {
    finish_error("action/name: missing or not a string");
    return;
  }
  const std::string name = action["name"].get<std::string>();
  const McpToolSpec* tool = catalog_.find_tool(name);
  if (tool == nullptr) {
    finish_error("unknown tool '" + name + "'; the tools are: " + tool_list(catalog_));
    return;
  }
  const nlohmann::json args = action.contains("args") && !action["args"].is_null() ? action["args"]
                                                                                    : nlohmann::json::object();
  if (auto problem = catalog_.check_args(*tool, args); !problem.empty()) {
    finish_error(problem);
    return;
  }
  if (name == "read_telemetry") return tool_read_telemetry(args);
  if (name == "takeoff") return tool_takeoff(args);
  if (name == "set_waypoint") return tool_set_waypoint(args);
  if (name == "navigate_to") return tool_navigate_to(args);
  if (name == "set_altitude") return tool_set_altitude(args);
  if (name == "adjust_speed") return tool_adjust_speed(args);
  if (name == "execute_maneuver") return tool_execute_maneuver(args);
  if (name == "hold") return tool_hold();
  if (name == "return_to_home") return tool_return_to_home();
  if (name == "land") return tool_land();
  if (name == "check_geofence") return tool_check_geofence(args);
  if (name == "activate_sensor") return tool_activate_sensor(args);
  if (name == "capture_image") return tool_capture_image(args);
  if (name == "switch_network_slice") return tool_switch_network_slice(args);
  finish_error("tool '" + name + "' is in the catalog but the vehicle does not implement it");
}

void ToolServerNode::handle_a2a(const nlohmann::json& action) {
  const std::string task = action.contains("task") && action["task"].is_string() ? action["task"].get<std::string>() : "";
  const std::string to = action.contains("to") && action["to"].is_string() ? action["to"].get<std::string>() : "";
  const auto fail = [&](const std::string& message) {
    ++counters_->errors;
    PeerAnswer a;
    a.status = "error";
    a.payload = {{"error", message}};
    finish(a2a_observation(task, to, a));
  };
  if (task.empty()) return fail("action/task: missing or not a string");
  const A2aTaskSpec* spec = catalog_.find_task(task);
  if (spec == nullptr) return fail("unknown task '" + task + "'; the tasks are: " + task_list(catalog_));
  if (to != spec->to) {
    return fail("action/to: task '" + task + "' is answered by '" + spec->to + "', not '" + to + "'");
  }
  const nlohmann::json payload = action.contains("payload") && !action["payload"].is_null()
                                     ? action["payload"]
                                     : nlohmann::json::object();
  if (auto problem = catalog_.check_payload(*spec, payload); !problem.empty()) return fail(problem);
  PeerAnswer answer;
  if (task == "collision_avoidance") {
    answer = swarm_.collision_avoidance(self_view(), payload);
  } else if (task == "swarm_status_check") {
    answer = swarm_.swarm_status_check(self_view());
  } else if (task == "swarm_formation") {
    answer = swarm_.swarm_formation(self_view(), payload);
  } else if (task == "request_weather_update") {
    answer = weather_.weather_update(self_view());
  } else if (task == "path_plan") {
    answer = ground_station_.path_plan(position(), payload);
  } else if (task == "handover_data") {
    answer = ground_station_.handover_data(images_, payload);
    counters_->image_bytes_downlinked += static_cast<uint64_t>(answer.extra_bytes);
  } else {
    return fail("task '" + task + "' is in the catalog but no peer implements it");
  }
  if (answer.status == "error") ++counters_->errors;
  finish(a2a_observation(task, spec->to, answer), answer.extra_bytes);
}

void ToolServerNode::finish(nlohmann::json obs, int64_t extra_bytes) {
  if (!current_) {
    common::log_error(kLog, "an observation without an action in progress was dropped");
    return;
  }
  ObservationEnvelope envelope{current_->turn, current_->action_index, std::move(obs)};
  const int64_t now_us = executor_->clock().now_us();
  bus_->publish(common::channels::kLinkDownTx,
                encode_observation(envelope, next_message_id_++, now_us, config_.sender, extra_bytes));
  ++counters_->observations_sent;
  current_.reset();
  busy_ = false;
  process_queue();
}

void ToolServerNode::finish_mcp(const nlohmann::json& result, int64_t extra_bytes) {
  finish(mcp_observation(current_->action.value("name", std::string()), result), extra_bytes);
}

void ToolServerNode::finish_error(const std::string& message) {
  ++counters_->errors;
  const std::string name = current_ && current_->action.contains("name") && current_->action["name"].is_string()
                               ? current_->action["name"].get<std::string>()
                               : "";
  finish(mcp_observation(name, error_result(message)));
}

void ToolServerNode::finish_gate_refusal(const std::string& reason) {
  ++counters_->gate_refusals;
  const std::string tool = current_->action.value("name", std::string());
  common::log_info(kLog, "gate refused " + tool + ": " + reason);
  a3lcm::safety_event_t e{};
  e.utime_us = executor_->clock().now_us();
  e.kind = "gate_refusal";
  e.source = config_.sender;
  const Eigen::Vector3d p = position().value_or(Eigen::Vector3d::Zero());
  for (int k = 0; k < 3; ++k) e.p_W_m[k] = p[k];
  e.value = 0.0;
  e.detail = tool + ": " + reason;
  bus_->publish(common::channels::kSafety, e);
  nlohmann::json result = refused_result(reason, "safety_gate");
  result["pose"] = pose_now();
  finish_mcp(result);
}

// ---------------------------------------------------------------------------------------------
// The fc

int32_t ToolServerNode::send_fc(int8_t command, const Eigen::Vector3d& target, double speed_mps, double yaw_deg) {
  a3lcm::fc_command_t c{};
  c.utime_us = executor_->clock().now_us();
  c.seq = ++seq_;
  c.command = command;
  for (int k = 0; k < 3; ++k) c.target_W_m[k] = target[k];
  c.speed_limit_mps = speed_mps;
  c.yaw_deg = yaw_deg;
  bus_->publish(common::channels::kFcCommand, c);
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

void ToolServerNode::await_slice_reply(int64_t request_id, SliceContinuation then) {
  awaited_slice_request_ = request_id;
  slice_then_ = std::move(then);
  slice_timer_ = executor_->schedule_after(seconds_to_us(config_.slice_reply_timeout_s), [this] {
    if (!slice_then_) return;
    ++counters_->timeouts;
    auto then = std::move(slice_then_);
    slice_then_ = nullptr;
    then(nullptr);
  });
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

void ToolServerNode::answer_motion(const a3lcm::fc_status_t* s, nlohmann::json extra) {
  if (s == nullptr) {
    char text[128];
    std::snprintf(text, sizeof text, "no status from the flight controller within %.1f s", config_.fc_status_timeout_s);
    finish_mcp({{"status", "timeout"}, {"reason", text}, {"pose", pose_now()}});
    return;
  }
  const Eigen::Vector3d p(s->p_W_m[0], s->p_W_m[1], s->p_W_m[2]);
  nlohmann::json result;
  if (s->last_command_accepted) {
    result = {{"status", "accepted"}};
  } else {
    result = refused_result(s->last_command_reason, "flight_controller");
  }
  result["mode"] = fc_mode_name(s->mode);
  result["pose"] = pose_json(p, s->yaw_deg);
  if (s->last_command_accepted) {
    for (auto& [key, value] : extra.items()) result[key] = value;
  }
  finish_mcp(result);
}

}  // namespace a3::agent
