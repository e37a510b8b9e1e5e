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
// rules, then (motion) by the safety gate; only then does anything reach the fc. Each tool and
// task is a handler registered by its catalog name (tool_handlers.hpp, vehicle_tools.hpp) that
// reaches the vehicle through VehicleServices; the node keeps the queue, the LCM inputs and
// outputs and the waits. The tools' semantics and observation shapes are in agent/README.md
// ("Vehicle side").
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
#include "common/node.hpp"
#include "vehicle/ground_shared.hpp"
#include "vehicle/ground_station.hpp"
#include "vehicle/image_store.hpp"
#include "vehicle/onboard_route.hpp"
#include "vehicle/safety_gate.hpp"
#include "vehicle/sensor_suite.hpp"
#include "vehicle/swarm_peer.hpp"
#include "vehicle/tool_server_config.hpp"
#include "vehicle/vehicle_services.hpp"
#include "vehicle/vehicle_tools.hpp"
#include "vehicle/weather_service.hpp"
#include "vehicle/wind_estimator.hpp"

namespace a3::vehicle {


class ToolServerNode final : public common::Node, private VehicleServices {
 public:
  // Throws std::invalid_argument naming the bad field of the config (or of env, sensors,
  // payloads, traffic), or a catalog tool/task without a handler or a handler without a
  // catalog entry (ToolHandlers::check_against). The catalog must outlive the node.
  explicit ToolServerNode(ToolServerConfig config, const ToolCatalog& catalog = ToolCatalog::builtin(),
                          const ToolHandlers& handlers = vehicle_tools());
  ~ToolServerNode() override;

  std::string name() const override { return "tool_server"; }
  // Subscribes the link's up RX, A3_FC_STATUS, A3_STATE, A3_NET and the slice replies; publishes
  // the link's down TX, A3_FC_CMD, the slice requests, A3_PAYLOAD, A3_SAFETY and (its peers)
  // A3_TRAFFIC.
  std::optional<common::NodePorts> ports() const override;
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
  const SafetyGate& gate() const override { return gate_; }
  const SensorSuite& sensors() const { return sensors_; }
  const OnboardRoute* route() const { return route_ ? &*route_ : nullptr; }
  const ToolServerConfig& config() const override { return config_; }
  const WindEstimator& wind_estimate() const override { return wind_; }

 private:
  struct AtomicCounters {
    explicit AtomicCounters(common::CounterSet& s)
        : link_messages(s.add("link_messages")), malformed_dropped(s.add("malformed_dropped")), queue_overflow_dropped(s.add("queue_overflow_dropped")), heartbeats_forwarded(s.add("heartbeats_forwarded")), mcp_calls(s.add("mcp_calls")), a2a_messages(s.add("a2a_messages")), errors(s.add("errors")), gate_refusals(s.add("gate_refusals")), fc_commands(s.add("fc_commands")), fc_refusals(s.add("fc_refusals")), timeouts(s.add("timeouts")), routes_started(s.add("routes_started")), routes_completed(s.add("routes_completed")), routes_aborted(s.add("routes_aborted")), images_captured(s.add("images_captured")), image_bytes_downlinked(s.add("image_bytes_downlinked")), observations_sent(s.add("observations_sent")), turn_messages(s.add("turn_messages")) {}
    common::Counter &link_messages, &malformed_dropped, &queue_overflow_dropped, &heartbeats_forwarded, &mcp_calls, &a2a_messages, &errors, &gate_refusals, &fc_commands, &fc_refusals, &timeouts, &routes_started, &routes_completed, &routes_aborted, &images_captured, &image_bytes_downlinked, &observations_sent, &turn_messages;
  };

  // Inputs.
  void on_link_message(const a3lcm::link_message_t& m);
  void on_fc_status(const a3lcm::fc_status_t& s);
  void on_slice_reply(const a3lcm::slice_switch_reply_t& r);
  void on_true_state(const a3lcm::vehicle_state_t& s);
  void publish_traffic();

  // The action queue and the dispatch by name to the handlers (tool_server_node.cpp).
  void process_queue();
  void handle(const ActionEnvelope& action);
  void handle_mcp(const nlohmann::json& action);
  void handle_a2a(const nlohmann::json& action);
  void finish(nlohmann::json obs, int64_t extra_bytes = 0);
  void advance_route(const a3lcm::fc_status_t& s);
  void true_pose(Eigen::Vector3d* p_W_m, double* yaw_deg) const;

  // What the handlers may do (vehicle_services.hpp; tool_server_services.cpp, self_view.cpp).
  void finish_mcp(const nlohmann::json& result, int64_t extra_bytes = 0) override;
  void finish_error(const std::string& message) override;
  void finish_gate_refusal(const std::string& reason) override;
  int32_t send_fc(int8_t command, const Eigen::Vector3d& target_W_m, double speed_mps, double yaw_deg) override;
  void await_status(int32_t seq, StatusContinuation then) override;
  const a3lcm::fc_status_t* fc_status() const override { return fc_status_ ? &*fc_status_ : nullptr; }
  std::optional<Eigen::Vector3d> position() const override;  // the fc's estimate
  nlohmann::json pose_now() const override;
  double speed_mps() const override { return speed_mps_; }
  void set_speed_mps(double speed_mps) override { speed_mps_ = speed_mps; }
  void set_takeoff_target(const Eigen::Vector3d& target_W_m) override { takeoff_target_W_m_ = target_W_m; }
  int32_t begin_route(OnboardRoute route) override;
  void cancel_route(const std::string& why) override;
  OnboardRoute* onboard_route() override { return route_ ? &*route_ : nullptr; }
  SensorSuite& sensor_suite() override { return sensors_; }
  ImageStore& image_store() override { return images_; }
  const ImageRecord& capture(const SensorInfo& sensor, bool downlink) override;
  void publish_payload_event(const std::string& kind, const std::string& sensor, const ImageRecord* image) override;
  void count_image_bytes_downlinked(int64_t bytes) override;
  const a3lcm::network_state_t* network_state() const override { return net_ ? &*net_ : nullptr; }
  void request_slice_switch(const std::string& slice, SliceContinuation then) override;
  SelfView self_view() const override;  // true state and the path it is about to fly
  SwarmPeer& swarm_peer() override { return swarm_; }
  const WeatherService& weather_service() const override { return weather_; }
  const GroundStation& ground_station() const override { return ground_station_; }
  double now_s() const override;
  int64_t now_us() const override;

  // The ground speed the energy model (and so the gate, the ETAs and the peers' view of our
  // track) assumes; its wind follows wind_. Made before config_, which shares it.
  std::shared_ptr<GroundSpeedModel> ground_speed_;
  ToolServerConfig config_;
  const ToolCatalog& catalog_;
  ToolHandlers handlers_;
  SafetyGate gate_;
  SensorSuite sensors_;
  SwarmPeer swarm_;
  WeatherService weather_;
  WindEstimator wind_;  // seeded by weather_'s forecast, learned from A3_STATE
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

}  // namespace a3::vehicle
