// The conversation loop.
#include "agent/conversation/conversation_node.hpp"

#include <algorithm>
#include <cmath>

#include "a3lcm/episode_event_t.hpp"
#include "agent/conversation/scripted_agent.hpp"
#include "agent/link_protocol.hpp"
#include "common/channels.hpp"
#include "common/log.hpp"

namespace a3::agent {
namespace {

constexpr int8_t kModeDisarmed = 0, kModeHold = 2;

// The α³-Bench turn's n_t object.
nlohmann::json net_vector(const std::string& slice, double lat_ms, double jitter_ms, double loss_pct,
                          double throughput_mbps, double edge_load) {
  return {{"slice", slice},         {"lat_ms", lat_ms},
          {"jitter_ms", jitter_ms}, {"loss_pct", loss_pct},
          {"throughput_mbps", throughput_mbps}, {"edge_load", edge_load}};
}

// The actions of a step that fit under kMaxActionsPerTurn with the `already` sent this turn;
// `refused` counts the rest.
nlohmann::json capped_actions(const nlohmann::json& decided, std::size_t already, int& refused) {
  nlohmann::json actions = nlohmann::json::array();
  if (!decided.is_array()) return actions;
  const std::size_t room = already >= kMaxActionsPerTurn ? 0 : kMaxActionsPerTurn - already;
  for (std::size_t i = 0; i < decided.size() && i < room; ++i) actions.push_back(decided[i]);
  refused += static_cast<int>(decided.size() - actions.size());
  return actions;
}

}  // namespace

ConversationNode::ConversationNode(ConversationConfig config, std::unique_ptr<Agent> agent, const ToolCatalog& tools)
    : config_(std::move(config)), agent_(std::move(agent)), tools_(tools), tracker_(config_.mission) {
  if (config_.min_turns < 2 || config_.max_turns < config_.min_turns) {
    throw std::invalid_argument("conversation: turn budget must satisfy 2 <= min <= max, got " +
                                std::to_string(config_.min_turns) + ".." + std::to_string(config_.max_turns));
  }
}

ConversationNode::~ConversationNode() {
  if (agent_thread_.joinable()) {
    agent_->stop_deciding();
    agent_thread_.join();
  }
}

double ConversationNode::now_s() const { return executor_->clock().now_us() * 1e-6 - start_s_; }

// In whole microseconds: a wait polled at a period that divides it ends exactly on a poll, not
// on one side or the other of it as the rounding of a difference of seconds falls.
bool ConversationNode::lasted(int64_t since_us, double span_s) const {
  return executor_->clock().now_us() - since_us >= std::llround(span_s * 1e6);
}

std::vector<Turn> ConversationNode::turns() const {
  std::lock_guard<std::mutex> lock(turns_mutex_);
  return turns_;
}


std::optional<common::NodePorts> ConversationNode::ports() const {
  namespace ch = common::channels;
  const common::VehicleId v = config_.vehicle;
  return common::NodePorts()
      .subscribes(ch::kNet.of(v))
      .subscribes(ch::kLinkRecord.of(v))
      .subscribes(ch::kLinkDownRx.of(v))
      .subscribes(ch::kState.of(v))
      .subscribes(ch::kFcStatus.of(v))
      .subscribes(ch::kPayload.of(v))
      .subscribes(ch::kTraffic)
      .publishes(ch::kLinkUpTx.of(v))
      .publishes(ch::kEpisode);
}

void ConversationNode::start(common::Executor& executor, common::Bus& bus) {
  executor_ = &executor;
  bus_ = &bus;
  start_s_ = executor.clock().now_us() * 1e-6;
  namespace ch = common::channels;
  const common::VehicleId v = config_.vehicle;
  bus.subscribe<a3lcm::network_state_t>(ch::kNet.of(v), [this](const a3lcm::network_state_t& n, int64_t) {
    net_ = n;
    have_net_ = true;
  });
  bus.subscribe<a3lcm::link_record_t>(ch::kLinkRecord.of(v),
                                      [this](const a3lcm::link_record_t& r, int64_t) { on_link_record(r); });
  bus.subscribe<a3lcm::link_message_t>(ch::kLinkDownRx.of(v),
                                       [this](const a3lcm::link_message_t& m, int64_t) { on_downlink(m); });
  bus.subscribe<a3lcm::vehicle_state_t>(ch::kState.of(v), [this](const a3lcm::vehicle_state_t& s, int64_t) {
    tracker_.on_state(s);
    if (!s.on_ground) has_flown_ = true;
    const double speed = std::sqrt(s.v_W_mps[0] * s.v_W_mps[0] + s.v_W_mps[1] * s.v_W_mps[1] + s.v_W_mps[2] * s.v_W_mps[2]);
    if (speed < config_.settle_speed_mps) {
      if (still_since_us_ < 0) still_since_us_ = executor_->clock().now_us();
    } else {
      still_since_us_ = -1;
    }
  });
  bus.subscribe<a3lcm::fc_status_t>(ch::kFcStatus.of(v),
                                    [this](const a3lcm::fc_status_t& s, int64_t) { tracker_.on_fc_status(s); });
  bus.subscribe<a3lcm::payload_event_t>(ch::kPayload.of(v),
                                        [this](const a3lcm::payload_event_t& e, int64_t) { tracker_.on_payload(e); });
  bus.subscribe<a3lcm::traffic_state_t>(ch::kTraffic, [this](const a3lcm::traffic_state_t& t, int64_t) {
    for (auto& known : traffic_) {
      if (known.id == t.id) {
        known = t;
        return;
      }
    }
    traffic_.push_back(t);
  });
  const auto hb_us = static_cast<int64_t>(config_.heartbeat_period_s * 1e6);
  heartbeat_timer_ = executor.schedule(executor.clock().now_us() + hb_us, hb_us, [this] {
    a3lcm::link_message_t hb;
    hb.utime_us = executor_->clock().now_us();
    hb.sent_utime_us = hb.utime_us;
    hb.message_id = next_message_id_++;
    hb.sender = config_.sender;
    hb.kind = "heartbeat";
    const std::string body = "{}";
    hb.payload.assign(body.begin(), body.end());
    hb.payload_length = static_cast<int32_t>(hb.payload.size());
    hb.payload_size_bytes = 64;
    bus_->publish(common::channels::kLinkUpTx.of(config_.vehicle), hb);
    ++counters_.heartbeats;
    agent_->on_mission_time(now_s());
  });
  executor.schedule_after(static_cast<int64_t>(config_.start_delay_s * 1e6), [this] { start_turn(); });
}

nlohmann::json ConversationNode::net_json() const {
  if (!have_net_) return net_vector("URLLC", 0.0, 0.0, 0.0, 0.0, 0.0);
  return net_vector(net_.slice, net_.lat_ms, net_.jitter_ms, net_.loss_pct, net_.throughput_mbps, net_.edge_load);
}

bool ConversationNode::settled() const {
  const int8_t mode = tracker_.fc_status().mode;
  return (mode == kModeHold || mode == kModeDisarmed) && still_since_us_ >= 0 &&
         lasted(still_since_us_, config_.settle_time_s);
}

AgentContext ConversationNode::make_context() const {
  AgentContext c;
  c.mission = &config_.mission;
  c.initial_state = config_.initial_state;
  c.airspace = config_.airspace_brief;
  c.dialogue = &turns_;
  c.tools = &tools_;
  c.net = current_.net;
  c.last_telemetry = last_telemetry_;
  c.turn_number = current_.number;
  c.max_turns = config_.max_turns;
  c.mission_time_s = now_s();
  c.step = step_;
  c.turn_actions = current_.actions;
  c.turn_obs = current_.obs;
  return c;
}

void ConversationNode::start_turn() {
  if (finished_ || interrupted_) return;
  current_ = Turn{};
  current_.number = static_cast<int>(turns_.size()) + 1;
  current_.speaker = current_.number % 2 == 1 ? "agent" : "user";
  current_.net = net_json();
  current_.started_s = now_s();
  in_turn_ = true;
  step_ = 1;
  turn_continues_ = false;
  if (current_.speaker == "agent") {
    ask_agent();
  } else {
    start_user_turn();
  }
}

bool ConversationNode::interrupt() {
  interrupted_ = true;
  const bool busy = agent_busy_.load();
  agent_->stop_deciding();
  return busy;
}

void ConversationNode::end_interrupted_turn() {
  in_turn_ = false;
  deciding_ = false;
  current_.decided_s = now_s();
  current_.finished_s = current_.decided_s;
  {
    std::lock_guard<std::mutex> lock(turns_mutex_);
    turns_.push_back(current_);
  }
  publish_turn(current_);
  finish("interrupted");
}

void ConversationNode::ask_agent() {
  deciding_ = true;
  agent_busy_ = true;
  if (!config_.agent_runs_in_thread) {
    AgentDecision d;
    try {
      d = agent_->decide(make_context());
    } catch (const std::exception& e) {
      d.error = e.what();
    }
    decided(std::move(d), -1.0);
    return;
  }
  // The world keeps flying while the agent thinks on its own thread.
  thread_started_s_ = now_s();
  agent_done_ = false;
  AgentContext context = make_context();
  std::vector<Turn> dialogue_copy = turns();
  agent_thread_ = std::thread([this, context, dialogue_copy]() mutable {
    context.dialogue = &dialogue_copy;
    try {
      thread_decision_ = agent_->decide(context);
    } catch (const std::exception& e) {
      thread_decision_ = AgentDecision{};
      thread_decision_.error = e.what();
    }
    agent_done_ = true;
  });
  poll_timer_ = executor_->schedule_every(10'000, [this] { poll_agent_thread(); });
}

void ConversationNode::poll_agent_thread() {
  if (!agent_done_) return;
  executor_->cancel(poll_timer_);
  agent_thread_.join();
  // The thinking time has already passed in the world: only the extra think time remains.
  decided(std::move(thread_decision_), now_s() - thread_started_s_);
}

void ConversationNode::record_step(const AgentDecision& d, double charged_s) {
  current_.steps = step_;
  current_.think_time_s += charged_s;
  if (d.intent.empty()) {
    const bool interrupted = d.error.rfind("interrupted", 0) == 0;
    current_.intent = interrupted ? "interrupted" : !d.error.empty() ? "agent_error" : (turn_continues_ ? "" : "no_action");
  } else {
    current_.intent = d.intent;
  }
  current_.text = d.error.empty() ? d.text : "agent error: " + d.error;
  if (step_ == 1) {
    current_.usage = d.usage;
    current_.attempts = d.attempts;
  } else {
    for (const auto& [key, value] : d.usage.items()) {
      if (value.is_number()) current_.usage[key] = current_.usage.value(key, 0.0) + value.get<double>();
    }
    current_.attempts = std::max(current_.attempts, d.attempts);
  }
  if (d.attempt_log.is_array()) {
    for (const auto& a : d.attempt_log) current_.attempt_log.push_back(a);
  }
}

void ConversationNode::decided(AgentDecision d, double measured_s) {
  const bool in_thread = measured_s >= 0.0;
  const double wait_s = std::max(0.0, d.think_time_s + (in_thread ? 0.0 : d.latency_s));
  const int refused_before = current_.refused_actions;
  nlohmann::json actions = capped_actions(d.actions, step_ == 1 ? 0 : current_.actions.size(), current_.refused_actions);
  if (current_.refused_actions > refused_before) {
    common::log_warn("conversation", "turn " + std::to_string(current_.number) + ": " +
                                         std::to_string(current_.refused_actions - refused_before) +
                                         " actions beyond the cap of " + std::to_string(kMaxActionsPerTurn) +
                                         " per turn refused");
  }
  turn_continues_ = d.turn_continues && d.error.empty() && !actions.empty();
  record_step(d, (in_thread ? measured_s : d.latency_s) + d.think_time_s);
  agent_busy_ = false;
  if (interrupted_) {
    end_interrupted_turn();
    return;
  }
  if (!d.error.empty()) common::log_warn("conversation", "turn " + std::to_string(current_.number) + ": " + d.error);
  executor_->schedule_after(static_cast<int64_t>(wait_s * 1e6), [this, actions] {
    current_.decided_s = now_s();
    dispatch(actions);
  });
}

void ConversationNode::start_user_turn() {
  user_wait_started_us_ = executor_->clock().now_us();
  user_timer_ = executor_->schedule_every(250'000, [this] { wait_for_user_trigger(); });
}

void ConversationNode::wait_for_user_trigger() {
  if (!lasted(user_wait_started_us_, config_.user_min_wait_s)) return;
  SupervisorView v;
  v.mission = &config_.mission;
  v.progress = tracker_.to_json();
  v.net = net_json();
  const bool hard = is_hard_network(v.net);
  v.network_degraded = hard && !degraded_at_last_user_turn_;
  const auto& s = tracker_.state();
  // Each approach of a peer is reported once; a yielding peer is being dealt with.
  std::string alert;
  for (const auto& t : traffic_) {
    const double d = std::sqrt(std::pow(t.p_W_m[0] - s.p_W_m[0], 2) + std::pow(t.p_W_m[1] - s.p_W_m[1], 2) +
                               std::pow(t.p_W_m[2] - s.p_W_m[2], 2));
    const bool known = std::find(alerted_peers_.begin(), alerted_peers_.end(), t.id) != alerted_peers_.end();
    if (d > 1.5 * config_.traffic_alert_distance_m && known) {
      alerted_peers_.erase(std::remove(alerted_peers_.begin(), alerted_peers_.end(), t.id), alerted_peers_.end());
    } else if (d < config_.traffic_alert_distance_m && !known && !s.on_ground && t.status != "yielding" && alert.empty()) {
      alert = t.id + " at " + std::to_string(static_cast<int>(d)) + " m";
      pending_alert_peer_ = t.id;
    }
  }
  v.traffic_alert = alert;
  v.landed_after_flight = has_flown_ && s.on_ground && !tracker_.fc_status().armed;
  int done = 0;
  std::string names;
  for (std::size_t i = 0; i < tracker_.progress().size(); ++i) {
    if (tracker_.progress()[i].done) {
      ++done;
      names += (names.empty() ? "" : ", ") + config_.mission.objectives[i].id;
    }
  }
  v.objectives_newly_done = done - done_at_last_user_turn_;
  v.newly_done_names = names;
  v.turn_number = current_.number;
  v.max_turns = config_.max_turns;
  const bool trigger = settled() || v.objectives_newly_done > 0 || v.network_degraded || !v.traffic_alert.empty() ||
                       v.landed_after_flight || lasted(user_wait_started_us_, config_.user_max_wait_s);
  if (!trigger) return;
  executor_->cancel(user_timer_);
  if (!v.traffic_alert.empty()) alerted_peers_.push_back(pending_alert_peer_);
  degraded_at_last_user_turn_ = hard;
  done_at_last_user_turn_ = done;
  const UserUtterance u = user_.speak(v);
  current_.intent = u.intent;
  current_.text = u.text;
  current_.decided_s = now_s();
  dispatch(u.actions);
}

void ConversationNode::on_link_record(const a3lcm::link_record_t& r) {
  if (!awaiting_record_ || r.sender != config_.sender || r.message_id != turn_message_id_) return;
  awaiting_record_ = false;
  executor_->cancel(record_timer_);
  current_.net = net_vector(r.slice, r.net_lat_ms, r.net_jitter_ms, r.net_loss_pct, r.net_throughput_mbps,
                            r.net_edge_load);
  if (r.outcome == a3lcm::link_record_t::DELIVERED) current_.delivered_s = r.delivery_utime_us * 1e-6 - start_s_;
  maybe_complete_turn();
}

void ConversationNode::maybe_complete_turn() {
  if (!in_turn_ || awaiting_record_ || deciding_) return;
  for (const auto& p : pending_) {
    if (!p.done) return;
  }
  if (turn_continues_) {
    // The next step of the same turn, outside the callback that completed this one.
    turn_continues_ = false;
    ++step_;
    deciding_ = true;
    executor_->schedule_after(0, [this] { ask_agent(); });
    return;
  }
  complete_turn();
}

void ConversationNode::publish_turn(const Turn& t) {
  nlohmann::json detail = t.to_json();
  detail["_rig"] = {{"started_s", t.started_s}, {"decided_s", t.decided_s}, {"finished_s", t.finished_s},
                    {"sent_s", t.sent_s}, {"delivered_s", t.delivered_s},
                    {"think_time_s", t.think_time_s}, {"usage", t.usage}, {"attempts", t.attempts}, {"text", t.text}};
  if (t.speaker == "agent") detail["_rig"]["steps"] = t.steps;
  if (t.attempt_log.is_array() && !t.attempt_log.empty()) detail["_rig"]["attempt_log"] = t.attempt_log;
  if (t.refused_actions > 0) {
    detail["_rig"]["refused_actions"] = {{"count", t.refused_actions},
                                         {"cap", kMaxActionsPerTurn},
                                         {"reason", "more than " + std::to_string(kMaxActionsPerTurn) +
                                                        " actions in one agent turn: not sent"}};
  }
  a3lcm::episode_event_t ev;
  ev.utime_us = executor_->clock().now_us();
  ev.turn = t.number;
  ev.speaker = t.speaker;
  ev.kind = "turn_end";
  ev.status = "running";
  ev.detail_json = detail.dump();
  bus_->publish(common::channels::kEpisode, ev);
}

void ConversationNode::complete_turn() {
  in_turn_ = false;
  current_.finished_s = now_s();
  {
    std::lock_guard<std::mutex> lock(turns_mutex_);
    turns_.push_back(current_);
  }
  publish_turn(current_);
  agent_->on_dialogue(turns_, false, "");
  const int t = current_.number;
  const bool landed = has_flown_ && tracker_.state().on_ground && !tracker_.fc_status().armed;
  if (t >= config_.max_turns) {
    finish("turn budget used");
    return;
  }
  if (t >= config_.min_turns && current_.speaker == "user" && landed) {
    finish("the vehicle has landed");
    return;
  }
  start_turn();
}

void ConversationNode::finish(const std::string& why) {
  // The ground station stays on the air (heartbeats) until the episode ends.
  finished_ = true;
  agent_->on_dialogue(turns_, true, why);
  a3lcm::episode_event_t ev;
  ev.utime_us = executor_->clock().now_us();
  ev.turn = static_cast<int32_t>(turns_.size());
  ev.speaker = "rig";
  ev.kind = "dialogue_end";
  ev.status = "running";
  ev.detail_json = nlohmann::json({{"reason", why}}).dump();
  bus_->publish(common::channels::kEpisode, ev);
}

}  // namespace a3::agent
