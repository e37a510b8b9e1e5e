// Faults an agent can bring into a turn: a reply with 10 000 actions sends kMaxActionsPerTurn
// of them and records the rest as refused (in the turn and in its published _rig), over all
// steps of a turn; a decision that hangs until it is stopped (Ctrl-C) ends its turn as
// "interrupted", published with its attempt log, and the dialogue with it. Virtual time.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "agent/conversation/conversation_node.hpp"
#include "common/runtime.hpp"
#include "tests/agent_conversation/fake_link.hpp"

namespace a3::agent {
namespace {

// Decides `per_step[i]` read_telemetry actions at step i + 1, continuing while steps remain.
class FloodingAgent final : public Agent {
 public:
  explicit FloodingAgent(std::vector<int> per_step) : per_step_(std::move(per_step)) {}
  std::string name() const override { return "flooding"; }
  AgentDecision decide(const AgentContext& c) override {
    AgentDecision d;
    d.intent = "flood";
    const int n = c.step <= static_cast<int>(per_step_.size()) ? per_step_[c.step - 1] : 0;
    for (int i = 0; i < n; ++i) d.actions.push_back(mcp("read_telemetry"));
    d.turn_continues = c.step < static_cast<int>(per_step_.size());
    return d;
  }

 private:
  std::vector<int> per_step_;
};

struct Flown {
  std::vector<Turn> turns;
  std::vector<nlohmann::json> published;
};

Flown fly(std::vector<int> per_step) {
  common::VirtualRuntime rt;
  FakeLink link;
  ConversationNode conversation(two_turns(), std::make_unique<FloodingAgent>(std::move(per_step)));
  rt.add(link);
  rt.add(conversation);
  rt.run_until(60'000'000);
  return {conversation.turns(), link.published_turns};
}

TEST(TurnFaults, AReplyWith10000ActionsSendsTheCapAndRecordsTheRestAsRefused) {
  const Flown f = fly({10000});
  ASSERT_EQ(f.turns.size(), 2u);
  EXPECT_EQ(f.turns[0].actions.size(), kMaxActionsPerTurn);
  EXPECT_EQ(f.turns[0].obs.size(), kMaxActionsPerTurn);
  EXPECT_EQ(f.turns[0].obs[kMaxActionsPerTurn - 1]["result"]["status"], "ok") << "the allowed ones were executed";
  EXPECT_EQ(f.turns[0].refused_actions, 10000 - static_cast<int>(kMaxActionsPerTurn));
  ASSERT_EQ(f.published.size(), 2u);
  const nlohmann::json& refused = f.published[0]["_rig"]["refused_actions"];
  EXPECT_EQ(refused["count"], 10000 - static_cast<int>(kMaxActionsPerTurn));
  EXPECT_EQ(refused["cap"], kMaxActionsPerTurn);
  EXPECT_FALSE(f.published[1]["_rig"].contains("refused_actions")) << "the supervisor's turn refused nothing";
}

TEST(TurnFaults, TheCapCountsEveryStepOfATurn) {
  const Flown f = fly({10, 10, 1});
  ASSERT_EQ(f.turns.size(), 2u);
  EXPECT_EQ(f.turns[0].actions.size(), kMaxActionsPerTurn);
  EXPECT_EQ(f.turns[0].refused_actions, 10 + 10 + 1 - static_cast<int>(kMaxActionsPerTurn));
}

TEST(TurnFaults, ATurnAtTheCapRefusesNothing) {
  const Flown f = fly({static_cast<int>(kMaxActionsPerTurn)});
  ASSERT_EQ(f.turns.size(), 2u);
  EXPECT_EQ(f.turns[0].actions.size(), kMaxActionsPerTurn);
  EXPECT_EQ(f.turns[0].refused_actions, 0);
  EXPECT_FALSE(f.published[0]["_rig"].contains("refused_actions"));
}

// Hangs in decide() until stop_deciding(), then returns what an interrupted LLM turn returns.
class HangingAgent final : public Agent {
 public:
  std::string name() const override { return "hanging"; }
  AgentDecision decide(const AgentContext&) override {
    deciding = true;
    while (!stopped) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    AgentDecision d;
    d.error = "interrupted: the run was stopped during attempt 1 of the turn";
    d.attempt_log = nlohmann::json::array({{{"attempt", 1}, {"outcome", "interrupted"}}});
    return d;
  }
  void stop_deciding() override { stopped = true; }
  std::atomic<bool> deciding{false}, stopped{false};
};

TEST(TurnFaults, AnInterruptedDecisionEndsItsTurnAsInterruptedAndTheDialogue) {
  common::VirtualRuntime rt;
  FakeLink link;
  auto agent = std::make_unique<HangingAgent>();
  HangingAgent& hanging = *agent;
  ConversationNode conversation(two_turns(), std::move(agent));
  rt.add(link);
  rt.add(conversation);
  std::atomic<bool> was_busy{false};
  std::thread ctrl_c([&] {
    while (!hanging.deciding) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    was_busy = conversation.interrupt();
  });
  rt.run_until(30'000'000);
  ctrl_c.join();
  EXPECT_TRUE(was_busy) << "interrupt() says a decision was in progress";
  EXPECT_TRUE(conversation.finished());
  const std::vector<Turn> turns = conversation.turns();
  ASSERT_EQ(turns.size(), 1u) << "no turn after the interrupted one";
  EXPECT_EQ(turns[0].intent, "interrupted");
  EXPECT_TRUE(turns[0].actions.empty());
  ASSERT_EQ(link.published_turns.size(), 1u);
  EXPECT_EQ(link.published_turns[0]["_rig"]["attempt_log"][0]["outcome"], "interrupted");
  EXPECT_EQ(link.published_turns[0]["_rig"]["text"].get<std::string>().rfind("agent error: interrupted:", 0), 0u);
}

}  // namespace
}  // namespace a3::agent
