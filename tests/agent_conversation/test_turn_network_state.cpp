// The network vector of a turn is the link's state when the turn's message crossed it, not when
// the turn began: a conversation on the virtual runtime, with a fake link emulator that says
// eMBB (degraded) on A3_NET at the start and switches to URLLC before the turns' messages cross.
// Each turn also records when its message was handed to the link and when it was delivered.
#include <gtest/gtest.h>

#include "a3lcm/link_record_t.hpp"
#include "a3lcm/network_state_t.hpp"
#include "agent/conversation/conversation_node.hpp"
#include "agent/link_protocol.hpp"
#include "common/channels.hpp"
#include "common/runtime.hpp"

namespace a3::agent {
namespace {

namespace ch = common::channels;

a3lcm::network_state_t net(const std::string& slice, double loss_pct, bool degraded) {
  a3lcm::network_state_t n{};
  n.slice = slice;
  n.lat_ms = slice == "URLLC" ? 7.5 : 40.0;
  n.jitter_ms = 1.0;
  n.loss_pct = loss_pct;
  n.throughput_mbps = 100.0;
  n.edge_load = 0.25;
  n.degraded = degraded;
  return n;
}

// Publishes `before` now and `after` from switch_us on; answers every uplink message with its
// link record (n_t of the moment it crosses, delivery 30 ms later) and every action with an
// observation.
class FakeLink final : public common::Node {
 public:
  FakeLink(int64_t switch_us) : switch_us_(switch_us) {}
  std::string name() const override { return "fake_link"; }
  void start(common::Executor& executor, common::Bus& bus) override {
    executor_ = &executor;
    bus_ = &bus;
    bus.publish(ch::kNet.of(0), net("eMBB", 1.65, true));
    executor.schedule_at(switch_us_, [this] { bus_->publish(ch::kNet.of(0), net("URLLC", 0.06, false)); });
    bus.subscribe<a3lcm::link_message_t>(ch::kLinkUpTx.of(0), [this](const a3lcm::link_message_t& m, int64_t) { on_up(m); });
  }

 private:
  void on_up(const a3lcm::link_message_t& m) {
    const int64_t now = executor_->clock().now_us();
    const a3lcm::network_state_t n = now >= switch_us_ ? net("URLLC", 0.06, false) : net("eMBB", 1.65, true);
    a3lcm::link_record_t r{};
    r.utime_us = now;
    r.direction = "up";
    r.message_id = m.message_id;
    r.sender = m.sender;
    r.kind = m.kind;
    r.sent_utime_us = m.sent_utime_us;
    r.size_bytes = m.payload_size_bytes;
    r.outcome = a3lcm::link_record_t::DELIVERED;
    r.delivery_utime_us = now + 30'000;
    r.slice = n.slice;
    r.net_lat_ms = n.lat_ms;
    r.net_jitter_ms = n.jitter_ms;
    r.net_loss_pct = n.loss_pct;
    r.net_throughput_mbps = n.throughput_mbps;
    r.net_edge_load = n.edge_load;
    r.net_degraded = n.degraded;
    bus_->publish(ch::kLinkRecord.of(0), r);
    if (m.kind != "mcp_call") return;
    std::string error;
    const auto action = decode_action(m, &error);
    ASSERT_TRUE(action) << error;
    executor_->schedule_after(30'000, [this, a = *action] {
      ObservationEnvelope o{a.turn, a.action_index, {{"tool", a.action.value("name", "")}, {"result", {{"status", "ok"}}}}};
      bus_->publish(ch::kLinkDownRx.of(0), encode_observation(o, next_id_++, executor_->clock().now_us(), "tool_server"));
    });
  }

  int64_t switch_us_;
  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  int64_t next_id_ = 1;
};

// Thinks 4 s, then reads the telemetry.
class SlowAgent final : public Agent {
 public:
  std::string name() const override { return "slow"; }
  AgentDecision decide(const AgentContext&) override {
    AgentDecision d;
    d.intent = "status_check";
    d.actions = nlohmann::json::array({{{"type", "mcp"}, {"name", "read_telemetry"}, {"args", nlohmann::json::object()}}});
    d.latency_s = 4.0;
    return d;
  }
};

TEST(TurnNetworkState, IsTheLinkStateWhenTheTurnsMessageCrossed) {
  common::VirtualRuntime rt;
  ConversationConfig config;
  config.mission.name = "test";
  config.min_turns = 2;
  config.max_turns = 2;
  config.user_min_wait_s = 1.0;
  config.user_max_wait_s = 2.0;
  // The agent's turn begins at 2 s on eMBB; the slice switches at 3 s; its message crosses at 6 s.
  FakeLink link(3'000'000);
  ConversationNode conversation(config, std::make_unique<SlowAgent>());
  rt.add(link);
  rt.add(conversation);
  rt.run_until(20'000'000);
  const std::vector<Turn> turns = conversation.turns();
  ASSERT_EQ(turns.size(), 2u);
  const Turn& agent = turns[0];
  EXPECT_EQ(agent.net["slice"], "URLLC") << agent.net.dump();
  EXPECT_DOUBLE_EQ(agent.net["loss_pct"].get<double>(), 0.06);
  EXPECT_NEAR(agent.started_s, 2.0, 1e-6);
  EXPECT_NEAR(agent.sent_s, 6.0, 1e-6);
  EXPECT_NEAR(agent.delivered_s, 6.03, 1e-6);
  // The supervisor's turn too: its message crossed after the switch.
  EXPECT_EQ(turns[1].net["slice"], "URLLC");
  EXPECT_GE(turns[1].sent_s, agent.finished_s);
  EXPECT_NEAR(turns[1].delivered_s - turns[1].sent_s, 0.03, 1e-6);
}

TEST(TurnNetworkState, WithoutALinkRecordTheTurnKeepsTheStateLastHeard) {
  // A link emulator that never answers must not hold the dialogue.
  common::VirtualRuntime rt;
  ConversationConfig config;
  config.min_turns = 2;
  config.max_turns = 2;
  config.user_min_wait_s = 1.0;
  config.user_max_wait_s = 2.0;
  config.observation_timeout_s = 3.0;
  struct NetOnly final : common::Node {
    std::string name() const override { return "net_only"; }
    void start(common::Executor&, common::Bus& bus) override { bus.publish(ch::kNet.of(0), net("mMTC", 0.5, false)); }
  } net_only;
  ConversationNode conversation(config, std::make_unique<SlowAgent>());
  rt.add(conversation);  // subscribed before the state is published
  rt.add(net_only);
  rt.run_until(30'000'000);
  const std::vector<Turn> turns = conversation.turns();
  ASSERT_EQ(turns.size(), 2u);
  EXPECT_EQ(turns[0].net["slice"], "mMTC");
  EXPECT_LT(turns[0].delivered_s, 0.0);  // never delivered
  EXPECT_TRUE(conversation.finished());
}

}  // namespace
}  // namespace a3::agent
