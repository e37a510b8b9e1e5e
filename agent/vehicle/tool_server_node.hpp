// The vehicle-side tool server: executes the agent's MCP tool calls against the live vehicle
// and answers its A2A messages from the simulated peers. Talks only LCM:
//   in   A3_LINK_UP_RX   link_message_t "mcp_call" | "a2a_message" (link_protocol.hpp) and
//                        "heartbeat" (forwarded to the fc as HEARTBEAT at once)
//        A3_FC_STATUS    fc_status_t (the fc's estimate, command results)
//        A3_STATE        vehicle_state_t (true state: image positions, the peers' view)
//        A3_NET          network_state_t (read_telemetry's link block)
//        A3_SLICE_REPLY  slice_switch_reply_t
//   out  A3_LINK_DOWN_TX observations, one per action, in the order the actions came
//        A3_FC_CMD       fc_command_t (seq increments per command; heartbeats reuse the last)
//        A3_SLICE_REQ    slice_switch_request_t
//        A3_PAYLOAD      payload_event_t (sensor on/off, captures)
//        A3_TRAFFIC      traffic_state_t per peer at traffic_rate_hz
//        A3_SAFETY       safety_event_t "gate_refusal" when the gate refuses a motion
// Actions are executed one at a time: one that waits (for the fc's status of its command, a
// slice-switch reply) holds the next ones back, so observations keep the actions' order.
// Every argument is checked against the tool catalog's schema, then by the tool's own range
// rules, then (motion) by the safety gate; only then does anything reach the fc. The tools'
// semantics and observation shapes are in agent/README.md ("Vehicle side").
#pragma once

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/link_message_t.hpp"
#include "a3lcm/network_state_t.hpp"
#include "a3lcm/slice_switch_reply_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "agent/link_protocol.hpp"
#include "agent/tool_catalog.hpp"
#include "agent/vehicle/ground_station.hpp"
#include "agent/vehicle/image_store.hpp"
#include "agent/vehicle/onboard_route.hpp"
#include "agent/vehicle/safety_gate.hpp"
#include "agent/vehicle/sensor_suite.hpp"
#include "agent/vehicle/swarm_peer.hpp"
#include "agent/vehicle/tool_server_config.hpp"
#include "agent/vehicle/weather_service.hpp"
#include "common/node.hpp"

namespace a3::agent {


class ToolServerNode final : public common::Node {
 public:
  // Throws std::invalid_argument naming the bad field of the config (or of env, sensors,
  // payloads, traffic). The catalog must outlive the node.
  explicit ToolServerNode(ToolServerConfig config, const ToolCatalog& catalog = ToolCatalog::builtin());
  ~ToolServerNode() override;

  std::string name() const override { return "tool_server"; }
  void start(common::Executor& executor, common::Bus& bus) override;

  // link_messages (received on A3_LINK_UP_RX), malformed_dropped (not a well-formed envelope,
  // or an unknown kind), queue_overflow_dropped (actions beyond max_queued_actions),
  // heartbeats_forwarded, mcp_calls, a2a_messages, errors (error observations), gate_refusals,
  // fc_commands (heartbeats not included), fc_refusals, timeouts (no fc status / slice reply
  // in time), routes_started, routes_completed, routes_aborted (by a failsafe, a refusal or a
  // newer motion command), images_captured, image_bytes_downlinked, observations_sent,
  // turn_messages (the dialogue's turn messages, which ask nothing).
  const common::CounterSet& counters() const override { return counter_set_; }
  // The executor's thread only (or after it stopped).
  const ImageStore& images() const { return images_; }
  const SwarmPeer& swarm() const { return swarm_; }
  const SafetyGate& gate() const { return gate_; }
  const SensorSuite& sensors() const { return sensors_; }
  const OnboardRoute* route() const { return route_ ? &*route_ : nullptr; }
  const ToolServerConfig& config() const { return config_; }

 private:
  struct AtomicCounters {
    explicit AtomicCounters(common::CounterSet& s)
        : link_messages(s.add("link_messages")), malformed_dropped(s.add("malformed_dropped")), queue_overflow_dropped(s.add("queue_overflow_dropped")), heartbeats_forwarded(s.add("heartbeats_forwarded")), mcp_calls(s.add("mcp_calls")), a2a_messages(s.add("a2a_messages")), errors(s.add("errors")), gate_refusals(s.add("gate_refusals")), fc_commands(s.add("fc_commands")), fc_refusals(s.add("fc_refusals")), timeouts(s.add("timeouts")), routes_started(s.add("routes_started")), routes_completed(s.add("routes_completed")), routes_aborted(s.add("routes_aborted")), images_captured(s.add("images_captured")), image_bytes_downlinked(s.add("image_bytes_downlinked")), observations_sent(s.add("observations_sent")), turn_messages(s.add("turn_messages")) {}
    common::Counter &link_messages, &malformed_dropped, &queue_overflow_dropped, &heartbeats_forwarded, &mcp_calls, &a2a_messages, &errors, &gate_refusals, &fc_commands, &fc_refusals, &timeouts, &routes_started, &routes_completed, &routes_aborted, &images_captured, &image_bytes_downlinked, &observations_sent, &turn_messages;
  };
  using StatusContinuation = std::function<void(const a3lcm::fc_status_t* status)>;  // nullptr: timed out
  using SliceContinuation = std::function<void(const a3lcm::slice_switch_reply_t* reply)>;

  // Inputs.
  void on_link_message(const a3lcm::link_message_t& m);
  void on_fc_status(const a3lcm::fc_status_t& s);
  void on_slice_reply(const a3lcm::slice_switch_reply_t& r);
  void publish_traffic();

  // The action queue.
  void process_queue();
  void handle(const ActionEnvelope& action);
  void handle_mcp(const nlohmann::json& action);
  void handle_a2a(const nlohmann::json& action);
  void finish(nlohmann::json obs, int64_t extra_bytes = 0);
  void finish_mcp(const nlohmann::json& result, int64_t extra_bytes = 0);
  void finish_error(const std::string& message);
  void finish_gate_refusal(const std::string& reason);

  // The fc.
  int32_t send_fc(int8_t command, const Eigen::Vector3d& target_W_m, double speed_mps, double yaw_deg);
  void await_status(int32_t seq, StatusContinuation then);
  void await_slice_reply(int64_t request_id, SliceContinuation then);
  void cancel_route(const std::string& why);
  void advance_route(const a3lcm::fc_status_t& s);
  std::optional<Eigen::Vector3d> position() const;  // the fc's estimate
  // The fc's position and battery, or false after answering a refusal (no telemetry yet).
  bool require_telemetry(Eigen::Vector3d* p_W_m, double* battery_pct);
  nlohmann::json pose_now() const;                  // the fc's estimate, or null
  void answer_motion(const a3lcm::fc_status_t* s, nlohmann::json accepted_extra);

  // Motion tools (motion_tools.cpp).
  void tool_takeoff(const nlohmann::json& args);
  void tool_set_waypoint(const nlohmann::json& args);
  void tool_set_altitude(const nlohmann::json& args);
  void tool_navigate_to(const nlohmann::json& args);
  void tool_execute_maneuver(const nlohmann::json& args);
  void tool_hold();
  void tool_land();
  void tool_return_to_home();
  void tool_adjust_speed(const nlohmann::json& args);
  void start_route(OnboardRoute route, nlohmann::json extra);
  // Query tools (query_tools.cpp).
  void tool_read_telemetry(const nlohmann::json& args);
  void tool_check_geofence(const nlohmann::json& args);
  // Sensor and network tools (payload_tools.cpp).
  void tool_activate_sensor(const nlohmann::json& args);
  void tool_capture_image(const nlohmann::json& args);
  void tool_switch_network_slice(const nlohmann::json& args);
  const ImageRecord& capture(const SensorInfo& sensor, bool downlink);
  void publish_payload_event(const std::string& kind, const std::string& sensor, const ImageRecord* image);
  // The peers' view of our vehicle (true state and the path it is about to fly).
  SelfView self_view() const;
  void true_pose(Eigen::Vector3d* p_W_m, double* yaw_deg) const;

  ToolServerConfig config_;
  const ToolCatalog& catalog_;
  SafetyGate gate_;
  SensorSuite sensors_;
  SwarmPeer swarm_;
  WeatherService weather_;
  GroundStation ground_station_;
  ImageStore images_;

  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  std::deque<ActionEnvelope> queue_;
  std::optional<ActionEnvelope> current_;
  bool busy_ = false;
  bool in_queue_loop_ = false;
  int64_t next_message_id_ = 1;

  int32_t seq_ = 0;
  int32_t awaited_seq_ = 0;
  StatusContinuation status_then_;
  common::TimerId status_timer_ = 0;
  int64_t next_slice_request_ = 1;
  int64_t awaited_slice_request_ = 0;
  SliceContinuation slice_then_;
  common::TimerId slice_timer_ = 0;

  std::optional<a3lcm::fc_status_t> fc_status_;
  std::optional<a3lcm::vehicle_state_t> true_state_;
  std::optional<a3lcm::network_state_t> net_;
  std::optional<OnboardRoute> route_;
  std::optional<Eigen::Vector3d> takeoff_target_W_m_;
  double speed_mps_;  // the cruise speed the fc flies at (as last set)

  common::CounterSet counter_set_;
  std::unique_ptr<AtomicCounters> counters_;
};

}  // namespace a3::agent
