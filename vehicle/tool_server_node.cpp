// The tool server's inputs, action queue, the dispatch of each action by name to its handler
// (tool_handlers.hpp) and the answers. What the handlers may do to the vehicle is in
// tool_server_services.cpp; the tools themselves in motion_tools.cpp, route_tools.cpp,
// query_tools.cpp, payload_tools.cpp and peer_tasks.cpp.
#include "vehicle/tool_server_node.hpp"

#include <cmath>
#include <limits>

#include "a3lcm/safety_event_t.hpp"
#include "common/channels.hpp"
#include "common/log.hpp"
#include "vehicle/observation_json.hpp"

namespace a3::vehicle {
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

const ToolServerConfig& validated(const ToolServerConfig& c) {
  c.validate();
  return c;
}

ToolServerConfig with_ground_speed(ToolServerConfig c, std::shared_ptr<const GroundSpeedModel> ground_speed) {
  c.energy.ground_speed = std::move(ground_speed);
  return c;
}

}  // namespace

ToolServerNode::ToolServerNode(ToolServerConfig config, const ToolCatalog& catalog, const ToolHandlers& handlers)
    : ground_speed_(std::make_shared<GroundSpeedModel>(config.airframe)),
      config_(with_ground_speed(validated(config), ground_speed_)),
      catalog_(catalog),
      handlers_(handlers),
      gate_(config_.airspace, config_.gate, config_.energy, config_.home_W_m),
      sensors_(config_.sensors, config_.images),
      swarm_(config_.airspace.traffic, config_.swarm),
      weather_(config_.env, config_.weather),
      wind_(config_.airframe, wind_from_report(weather_.wind_mps(), weather_.wind_dir_deg())),
      ground_station_(gate_, config_.planner),
      speed_mps_(config_.energy.cruise_speed_mps),
      counters_(std::make_unique<AtomicCounters>(counter_set_)) {
  handlers_.check_against(catalog_);
  ground_speed_->set_wind_W_mps(wind_.wind_W_mps());
}

ToolServerNode::~ToolServerNode() = default;

std::optional<common::NodePorts> ToolServerNode::ports() const {
  namespace ch = common::channels;
  const common::VehicleId v = config_.vehicle;
  return common::NodePorts()
      .subscribes(ch::kLinkUpRx.of(v))
      .subscribes(ch::kFcStatus.of(v))
      .subscribes(ch::kState.of(v))
      .subscribes(ch::kNet.of(v))
      .subscribes(ch::kSliceReply.of(v))
      .publishes(ch::kLinkDownTx.of(v))
      .publishes(ch::kFcCommand.of(v))
      .publishes(ch::kSliceRequest.of(v))
      .publishes(ch::kPayload.of(v))
      .publishes(ch::kSafety.of(v))
      .publishes(ch::kTraffic);  // its peers' states (none without peers)
}

void ToolServerNode::start(common::Executor& executor, common::Bus& bus) {
  executor_ = &executor;
  bus_ = &bus;
  namespace ch = common::channels;
  const common::VehicleId v = config_.vehicle;
  bus.subscribe<a3lcm::link_message_t>(ch::kLinkUpRx.of(v),
                                       [this](const a3lcm::link_message_t& m, int64_t) { on_link_message(m); });
  bus.subscribe<a3lcm::fc_status_t>(ch::kFcStatus.of(v),
                                    [this](const a3lcm::fc_status_t& s, int64_t) { on_fc_status(s); });
  bus.subscribe<a3lcm::vehicle_state_t>(ch::kState.of(v),
                                        [this](const a3lcm::vehicle_state_t& s, int64_t) { on_true_state(s); });
  bus.subscribe<a3lcm::network_state_t>(ch::kNet.of(v),
                                        [this](const a3lcm::network_state_t& n, int64_t) { net_ = n; });
  bus.subscribe<a3lcm::slice_switch_reply_t>(
      ch::kSliceReply.of(v), [this](const a3lcm::slice_switch_reply_t& r, int64_t) { on_slice_reply(r); });
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
    bus_->publish(common::channels::kFcCommand.of(config_.vehicle), c);
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

void ToolServerNode::on_true_state(const a3lcm::vehicle_state_t& s) {
  true_state_ = s;
  WindSample sample;
  sample.t_s = static_cast<double>(s.utime_us) * 1e-6;
  sample.v_W_mps = Eigen::Vector3d(s.v_W_mps[0], s.v_W_mps[1], s.v_W_mps[2]);
  sample.q_WB = Eigen::Quaterniond(s.q_WB[0], s.q_WB[1], s.q_WB[2], s.q_WB[3]);
  sample.f_B_mps2 = Eigen::Vector3d(s.a_B_mps2[0], s.a_B_mps2[1], s.a_B_mps2[2]);
  sample.on_ground = s.on_ground;
  wind_.add(sample);
  ground_speed_->set_wind_W_mps(wind_.wind_W_mps());
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
  const ToolHandler* handler = handlers_.find_tool(name);
  if (handler == nullptr) {  // check_against at construction rules this out
    finish_error("tool '" + name + "' is in the catalog but the vehicle does not implement it");
    return;
  }
  (*handler)(*this, args);
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
  const TaskHandler* handler = handlers_.find_task(task);
  if (handler == nullptr) return fail("task '" + task + "' is in the catalog but no peer implements it");
  const PeerAnswer answer = (*handler)(*this, payload);
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
  bus_->publish(common::channels::kLinkDownTx.of(config_.vehicle),
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
  bus_->publish(common::channels::kSafety.of(config_.vehicle), e);
  nlohmann::json result = refused_result(reason, "safety_gate");
  result["pose"] = pose_now();
  finish_mcp(result);
}

}  // namespace a3::vehicle
