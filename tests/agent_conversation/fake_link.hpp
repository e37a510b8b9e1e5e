// A fake emulated link for the conversation's tests (virtual time): delivers every uplink
// message 20 ms later (its link record) and answers every action with an "ok" observation
// naming the tool, 50 ms later; counts the turn messages and keeps the turns published on
// A3_EPISODE.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "a3lcm/episode_event_t.hpp"
#include "a3lcm/link_record_t.hpp"
#include "agent/conversation/conversation_node.hpp"
#include "agent/link_protocol.hpp"
#include "common/channels.hpp"
#include "common/node.hpp"

namespace a3::agent {

namespace ch = common::channels;

class FakeLink final : public common::Node {
 public:
  std::string name() const override { return "fake_link"; }
  void start(common::Executor& executor, common::Bus& bus) override {
    executor_ = &executor;
    bus_ = &bus;
    bus.subscribe<a3lcm::link_message_t>(ch::kLinkUpTx.of(0), [this](const a3lcm::link_message_t& m, int64_t) { on_up(m); });
    bus.subscribe<a3lcm::episode_event_t>(ch::kEpisode, [this](const a3lcm::episode_event_t& e, int64_t) {
      if (e.kind == "turn_end") published_turns.push_back(nlohmann::json::parse(e.detail_json));
    });
  }
  int turn_messages = 0;
  std::vector<nlohmann::json> published_turns;

 private:
  void on_up(const a3lcm::link_message_t& m) {
    const int64_t now = executor_->clock().now_us();
    a3lcm::link_record_t r{};
    r.utime_us = now;
    r.direction = "up";
    r.message_id = m.message_id;
    r.sender = m.sender;
    r.kind = m.kind;
    r.outcome = a3lcm::link_record_t::DELIVERED;
    r.delivery_utime_us = now + 20'000;
    r.slice = "URLLC";
    bus_->publish(ch::kLinkRecord.of(0), r);
    if (m.kind == "turn") ++turn_messages;
    if (m.kind != "mcp_call") return;
    std::string error;
    const auto action = decode_action(m, &error);
    ASSERT_TRUE(action) << error;
    executor_->schedule_after(50'000, [this, a = *action] {
      ObservationEnvelope o{a.turn, a.action_index, {{"tool", a.action.value("name", "")}, {"result", {{"status", "ok"}}}}};
      bus_->publish(ch::kLinkDownRx.of(0), encode_observation(o, next_id_++, executor_->clock().now_us(), "tool_server"));
    });
  }

  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  int64_t next_id_ = 1;
};

inline nlohmann::json mcp(const std::string& name) {
  return {{"type", "mcp"}, {"name", name}, {"args", nlohmann::json::object()}};
}

// A two-turn mission whose supervisor answers after 1 to 2 s.
inline ConversationConfig two_turns() {
  ConversationConfig config;
  config.mission.name = "test";
  config.min_turns = 2;
  config.max_turns = 2;
  config.user_min_wait_s = 1.0;
  config.user_max_wait_s = 2.0;
  return config;
}

}  // namespace a3::agent
