// The conversation's exchange over the link: a turn's message and actions sent on the uplink, their
// observations matched back from the downlink, and the timeouts that stand in for the lost ones.
#include "agent/conversation/conversation_node.hpp"

#include "agent/link_protocol.hpp"
#include "common/channels.hpp"
#include "common/log.hpp"

namespace a3::agent {
namespace {

nlohmann::json timeout_observation(const nlohmann::json& action) {
  if (action.value("type", "") == "a2a") {
    return {{"task", action.value("task", "")},
            {"from", action.value("to", "")},
            {"status", "timeout"},
            {"payload", nlohmann::json::object()}};
  }
  return {{"tool", action.value("name", "")}, {"result", {{"status", "timeout"}}}};
}

bool is_image_action(const nlohmann::json& action) {
  return action.value("type", "") == "mcp" && action.value("name", "") == "capture_image" &&
         !(action.contains("args") && action["args"].is_object() && action["args"].value("store_only", false));
}

}  // namespace

void ConversationNode::send_turn_message() {
  turn_message_id_ = next_message_id_++;
  const std::string body = nlohmann::json({{"turn", current_.number}, {"speaker", current_.speaker},
                                           {"intent", current_.intent}, {"text", current_.text}})
                               .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  a3lcm::link_message_t m;
  m.utime_us = executor_->clock().now_us();
  m.sent_utime_us = m.utime_us;
  m.message_id = turn_message_id_;
  m.sender = config_.sender;
  m.kind = "turn";
  m.payload.assign(body.begin(), body.end());
  m.payload_length = static_cast<int32_t>(m.payload.size());
  m.payload_size_bytes = m.payload_length;
  current_.sent_s = now_s();
  awaiting_record_ = true;
  bus_->publish(common::channels::kLinkUpTx.of(config_.vehicle), m);
  // A link emulator that never answers must not hold the dialogue: keep the n_t heard last.
  record_timer_ = executor_->schedule_after(2'000'000, [this] {
    if (!awaiting_record_) return;
    awaiting_record_ = false;
    current_.net = net_json();
    maybe_complete_turn();
  });
}

void ConversationNode::dispatch(const nlohmann::json& actions) {
  deciding_ = false;
  if (step_ == 1) {
    current_.actions = nlohmann::json::array();
    current_.obs = nlohmann::json::array();
    pending_.clear();
    send_turn_message();
  }
  // A later step's actions follow the earlier ones in the turn, indexed on.
  for (const auto& action : actions) {
    const std::size_t i = current_.actions.size();
    current_.actions.push_back(action);
    current_.obs.push_back(nullptr);
    pending_.push_back(Pending{});
    ActionEnvelope env{current_.number, static_cast<int>(i), action};
    const auto msg = encode_action(env, next_message_id_++, executor_->clock().now_us(), config_.sender);
    bus_->publish(common::channels::kLinkUpTx.of(config_.vehicle), msg);
    ++counters_.actions_sent;
    const double timeout_s = is_image_action(action) ? config_.image_timeout_s : config_.observation_timeout_s;
    pending_[i].timer = executor_->schedule_after(static_cast<int64_t>(timeout_s * 1e6), [this, i] { on_action_timeout(i); });
  }
  maybe_complete_turn();  // a step without actions (after the first) ends the turn here
}

void ConversationNode::on_downlink(const a3lcm::link_message_t& m) {
  std::string error;
  auto env = decode_observation(m, &error);
  if (!env) {
    ++counters_.malformed;
    common::log_warn("conversation", "dropped a downlink message: " + error);
    return;
  }
  if (!in_turn_ || env->turn != current_.number || env->action_index < 0 ||
      static_cast<std::size_t>(env->action_index) >= pending_.size() || pending_[env->action_index].done) {
    ++counters_.stale;
    return;
  }
  const auto i = static_cast<std::size_t>(env->action_index);
  pending_[i].done = true;
  executor_->cancel(pending_[i].timer);
  current_.obs[i] = env->obs;
  ++counters_.observations;
  if (env->obs.value("tool", "") == "read_telemetry" && env->obs.contains("result")) last_telemetry_ = env->obs["result"];
  maybe_complete_turn();
}

void ConversationNode::on_action_timeout(std::size_t i) {
  if (i >= pending_.size() || pending_[i].done) return;
  pending_[i].done = true;
  current_.obs[i] = timeout_observation(current_.actions[i]);
  ++counters_.timeouts;
  maybe_complete_turn();
}

}  // namespace a3::agent
