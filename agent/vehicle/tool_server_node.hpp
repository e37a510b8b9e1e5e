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

struct ToolServerCounters {
  uint64_t link_messages = 0;           // received on A3_LINK_UP_RX
  uint64_t malformed_dropped = 0;       // not a well-formed envelope, or an unknown kind: logged, dropped
  uint64_t queue_overflow_dropped = 0;  // actions beyond max_queued_actions: logged, dropped
  uint64_t heartbeats_forwarded = 0;
  uint64_t mcp_calls = 0;
  uint64_t a2a_messages = 0;
  uint64_t errors = 0;                  // error observations (unknown tool/task, bad arguments)
  uint64_t gate_refusals = 0;
  uint64_t fc_commands = 0;             // on A3_FC_CMD, heartbeats not included
  uint64_t fc_refusals = 0;             // commands the fc refused (as its status said)
  uint64_t timeouts = 0;                // no fc status / slice reply in time
  uint64_t routes_started = 0;
  uint64_t routes_completed = 0;
  uint64_t routes_aborted = 0;          // by a failsafe, a refusal or a newer motion command
  uint64_t images_captured = 0;
  uint64_t image_bytes_downlinked = 0;  // bytes charged to the downlink for images
  uint64_t observations_sent = 0;
};

class ToolServerNode final : public common::Node {
 public:
  // Throws std::invalid_argument naming the bad field of the config (or of env, sensors,
  // payloads, traffic). The catalog must outlive the node.
  explicit ToolServerNode(ToolServerConfig config, const ToolCatalog& catalog = ToolCatalog::builtin());
  ~ToolServerNode() override;

  std::string name() const override { return "tool_server"; }
  void start(common::Executor& executor, common::Bus& bus) override;

  // Safe from any thread.
  ToolServerCounters counters() const;
  // The executor's thread only (or after it stopped).
  const ImageStore& images() const { return images_; }
  const SwarmPeer& swarm() const { return swarm_; }
  const SafetyGate& gate() const { return gate_; }
  const SensorSuite& sensors() const { return sensors_; }
  const OnboardRoute* route() const { return route_ ? &*route_ : nullptr; }
  const ToolServerConfig& config() const { return config_; }

 private:
  struct AtomicCounters {
    std::atomic<uint64_t> link_messages{0}, malformed_dropped{0}, queue_overflow_dropped{0}, heartbeats_forwarded{0},
        mcp_calls{0}, a2a_messages{0}, errors{0}, gate_refusals{0}, fc_commands{0}, fc_refusals{0}, timeouts{0},
        routes_started{0}, routes_completed{0}, routes_aborted{0}, images_captured{0}, image_bytes_downlinked{0},
        observations_sent{0};
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

  std::unique_ptr<AtomicCounters> counters_;
};

}  // namespace a3::agent
