// The ground side of an episode: runs the conversation of SPEC §1 — strict alternation
// starting with the agent, 8..12 turns — between an agent and the simulated supervisor. Each
// turn, when its speaker has decided, sends one "turn" message up the emulated link
// (A3_LINK_UP_TX) and then its actions; the turn's n_t is the link's state when that message
// crossed (its A3_LINK_RECORD), and the turn ends when that record is in and every
// observation has come down (A3_LINK_DOWN_RX) or timed out. The
// agent's latency passes in the simulated world before its actions leave. An agent turn may
// take several steps (AgentDecision::turn_continues): each step's actions go out after its
// latency, and when their observations are in the agent decides again for the same turn; the
// turn ends after a step that does not continue. Between turns the
// world keeps flying: the supervisor speaks when the vehicle has settled, an objective is
// done, the link degrades, traffic comes close, or after a maximum wait. Completed turns go
// out on A3_EPISODE; command heartbeats go up the link every second.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/link_message_t.hpp"
#include "a3lcm/link_record_t.hpp"
#include "a3lcm/network_state_t.hpp"
#include "a3lcm/payload_event_t.hpp"
#include "a3lcm/traffic_state_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "agent/conversation/agent.hpp"
#include "agent/conversation/simulated_user.hpp"
#include "agent/mission/mission_tracker.hpp"
#include "common/node.hpp"

namespace a3::agent {

struct ConversationConfig {
  common::VehicleId vehicle = 0;    // the vehicle the agent flies: its link, state and payload channels
  Mission mission;
  nlohmann::json initial_state;     // the scenario's α³-Bench initial_state
  nlohmann::json airspace_brief;    // what agents are told of no-fly zones and traffic
  int min_turns = 8;
  int max_turns = 12;
  double start_delay_s = 2.0;       // first turn: after the sensors and estimator settle
  double observation_timeout_s = 15.0;
  double image_timeout_s = 120.0;
  double user_min_wait_s = 3.0;
  double user_max_wait_s = 300.0;
  double settle_speed_mps = 0.3;
  double settle_time_s = 3.0;
  double heartbeat_period_s = 1.0;
  double traffic_alert_distance_m = 120.0;
  // Real time with an agent whose decide() blocks (an HTTP call): run it on a thread so the
  // world keeps flying, and charge its real duration. Otherwise decide() runs in place and its
  // declared latency is charged.
  bool agent_runs_in_thread = false;
  std::string sender = "ground_station";
};

class ConversationNode final : public common::Node {
 public:
  ConversationNode(ConversationConfig config, std::unique_ptr<Agent> agent,
                   const ToolCatalog& tools = ToolCatalog::builtin());
  ~ConversationNode() override;

  std::string name() const override { return "conversation"; }
  // Subscribes the vehicle's A3_NET, A3_LINK_RECORD, the link's down RX, A3_STATE, A3_FC_STATUS,
  // A3_PAYLOAD and A3_TRAFFIC; publishes the link's up TX and A3_EPISODE.
  std::optional<common::NodePorts> ports() const override;
  void start(common::Executor& executor, common::Bus& bus) override;

  bool finished() const { return finished_.load(); }
  // Ctrl-C, from any thread: an agent decision in progress is stopped (Agent::stop_deciding),
  // its turn is recorded as it stands (intent "interrupted", the attempt log so far) and
  // published on A3_EPISODE, and the dialogue ends. Returns whether a decision was in progress.
  bool interrupt();
  // Snapshots, safe from any thread.
  std::vector<Turn> turns() const;
  // actions_sent, observations, timeouts, stale_observations (for an earlier turn, arrived
  // too late), malformed, heartbeats.
  const common::CounterSet& counters() const override { return counter_set_; }

 private:
  struct Pending {
    bool done = false;
    common::TimerId timer = 0;
  };
  void start_turn();
  // Asks the agent for the next step of its turn (in place, or on a thread).
  void ask_agent();
  void poll_agent_thread();
  void decided(AgentDecision decision, double extra_delay_s);
  // After interrupt(): the decided step ends its turn without dispatching, and the dialogue.
  void end_interrupted_turn();
  // The decision's effect on the turn: intent, text, latency, usage, attempts (all steps).
  void record_step(const AgentDecision& d, double charged_s);
  void start_user_turn();
  void wait_for_user_trigger();
  void dispatch(const nlohmann::json& actions);
  void on_downlink(const a3lcm::link_message_t& m);
  void on_action_timeout(std::size_t index);
  void complete_turn();
  // Completes the turn once every action is answered and its link record is in.
  void maybe_complete_turn();
  void send_turn_message();
  void on_link_record(const a3lcm::link_record_t& r);
  void publish_turn(const Turn& t);
  void finish(const std::string& why);
  AgentContext make_context() const;
  nlohmann::json net_json() const;
  double now_s() const;
  bool lasted(int64_t since_us, double span_s) const;  // since_us on the executor's clock
  bool settled() const;

  ConversationConfig config_;
  std::unique_ptr<Agent> agent_;
  const ToolCatalog& tools_;
  SimulatedUser user_;
  MissionTracker tracker_;
  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  double start_s_ = 0.0;

  mutable std::mutex turns_mutex_;
  std::vector<Turn> turns_;
  Turn current_;
  std::vector<Pending> pending_;
  bool in_turn_ = false;
  int step_ = 1;                // of the agent's turn
  bool deciding_ = false;       // a step is being decided or waits out its latency
  bool turn_continues_ = false; // the last step asked for another
  int64_t next_message_id_ = 1;
  int64_t turn_message_id_ = -1;
  bool awaiting_record_ = false;
  common::TimerId record_timer_ = 0;

  a3lcm::network_state_t net_{};
  bool have_net_ = false;
  bool degraded_at_last_user_turn_ = false;
  int64_t still_since_us_ = -1;  // on the executor's clock; < 0: moving
  int64_t user_wait_started_us_ = 0;
  int done_at_last_user_turn_ = 0;
  bool has_flown_ = false;
  nlohmann::json last_telemetry_;
  std::vector<a3lcm::traffic_state_t> traffic_;
  std::vector<std::string> alerted_peers_;  // approaches already reported
  std::string pending_alert_peer_;

  // A decision running on a thread (real time, blocking agent).
  std::thread agent_thread_;
  std::atomic<bool> agent_done_{false};
  AgentDecision thread_decision_;
  double thread_started_s_ = 0.0;
  common::TimerId poll_timer_ = 0;
  common::TimerId user_timer_ = 0;
  common::TimerId heartbeat_timer_ = 0;

  std::atomic<bool> finished_{false};
  std::atomic<bool> agent_busy_{false};   // decide() is running (in place or on its thread)
  std::atomic<bool> interrupted_{false};
  common::CounterSet counter_set_;
  struct Counters {
    explicit Counters(common::CounterSet& s)
        : actions_sent(s.add("actions_sent")), observations(s.add("observations")), timeouts(s.add("timeouts")), stale(s.add("stale_observations")), malformed(s.add("malformed")), heartbeats(s.add("heartbeats")) {}
    common::Counter &actions_sent, &observations, &timeouts, &stale, &malformed, &heartbeats;
  } counters_{counter_set_};
};

}  // namespace a3::agent
