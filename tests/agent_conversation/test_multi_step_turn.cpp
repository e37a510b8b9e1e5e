// An agent turn of several steps (AgentDecision::turn_continues), as an MCP client takes it:
// each step's actions go out after its latency, the agent decides again with the turn so far
// once their observations are in, the turn's message crosses the link once (at the first
// step), latencies add up, and intent and text are the last step's. Virtual time, fake link.
#include <gtest/gtest.h>

#include "agent/conversation/conversation_node.hpp"
#include "common/runtime.hpp"
#include "tests/agent_conversation/fake_link.hpp"

namespace a3::agent {
namespace {

// Step 1: read_telemetry (1 s); step 2: check_geofence (2 s); step 3: ends the turn (0.5 s).
// Records what it saw of the turn so far at each step.
class ThreeStepAgent final : public Agent {
 public:
  std::string name() const override { return "three_step"; }
  AgentDecision decide(const AgentContext& c) override {
    seen_steps.push_back(c.step);
    seen_obs.push_back(c.turn_obs);
    AgentDecision d;
    if (c.step == 1) {
      d.actions = nlohmann::json::array({mcp("read_telemetry")});
      d.latency_s = 1.0;
      d.turn_continues = true;
    } else if (c.step == 2) {
      d.actions = nlohmann::json::array({mcp("check_geofence")});
      d.latency_s = 2.0;
      d.turn_continues = true;
    } else {
      d.intent = "status_check";
      d.text = "All checked.";
      d.latency_s = 0.5;
    }
    return d;
  }
  void on_dialogue(const std::vector<Turn>& dialogue, bool over, const std::string& why) override {
    dialogue_sizes.push_back(dialogue.size());
    if (over) over_why = why;
  }
  std::vector<int> seen_steps;
  std::vector<nlohmann::json> seen_obs;
  std::vector<std::size_t> dialogue_sizes;
  std::string over_why;
};

TEST(MultiStepTurn, EachStepSeesTheObservationsOfTheStepsBefore) {
  common::VirtualRuntime rt;
  FakeLink link;
  auto agent = std::make_unique<ThreeStepAgent>();
  ThreeStepAgent& seen = *agent;
  ConversationNode conversation(two_turns(), std::move(agent));
  rt.add(link);
  rt.add(conversation);
  rt.run_until(30'000'000);
  ASSERT_EQ(seen.seen_steps, (std::vector<int>{1, 2, 3}));
  EXPECT_TRUE(seen.seen_obs[0].empty());
  ASSERT_EQ(seen.seen_obs[1].size(), 1u);
  EXPECT_EQ(seen.seen_obs[1][0]["tool"], "read_telemetry");
  ASSERT_EQ(seen.seen_obs[2].size(), 2u);
  EXPECT_EQ(seen.seen_obs[2][1]["tool"], "check_geofence");
}

TEST(MultiStepTurn, IsOneTurnWithEveryStepsActionsAndTheLastStepsWords) {
  common::VirtualRuntime rt;
  FakeLink link;
  auto agent = std::make_unique<ThreeStepAgent>();
  ThreeStepAgent& seen = *agent;
  ConversationNode conversation(two_turns(), std::move(agent));
  rt.add(link);
  rt.add(conversation);
  rt.run_until(30'000'000);
  const std::vector<Turn> turns = conversation.turns();
  ASSERT_EQ(turns.size(), 2u);
  const Turn& t = turns[0];
  ASSERT_EQ(t.actions.size(), 2u);
  EXPECT_EQ(t.actions[0]["name"], "read_telemetry");
  EXPECT_EQ(t.actions[1]["name"], "check_geofence");
  ASSERT_EQ(t.obs.size(), 2u);
  EXPECT_EQ(t.obs[1]["tool"], "check_geofence");
  EXPECT_EQ(t.intent, "status_check");
  EXPECT_EQ(t.text, "All checked.");
  EXPECT_EQ(t.steps, 3);
  EXPECT_NEAR(t.think_time_s, 3.5, 1e-9);
  // The turn's message left once, after the first step's latency (turn begins at 2 s).
  EXPECT_NEAR(t.sent_s, 3.0, 1e-6);
  EXPECT_EQ(link.turn_messages, 2);  // the agent's turn and the supervisor's
  // Steps: 1 s + 50 ms observation, 2 s + 50 ms, then 0.5 s: the turn ends at 5.6 s.
  EXPECT_NEAR(t.finished_s, 2.0 + 1.05 + 2.05 + 0.5, 1e-3);
  EXPECT_EQ(seen.over_why, "turn budget used");
  EXPECT_EQ(seen.dialogue_sizes, (std::vector<std::size_t>{1, 2, 2}));
}

// Asks to continue but gives nothing to do: the turn ends rather than asking forever.
class EmptyContinuingAgent final : public Agent {
 public:
  std::string name() const override { return "empty"; }
  AgentDecision decide(const AgentContext&) override {
    ++calls;
    AgentDecision d;
    d.intent = "idle";
    d.turn_continues = true;
    return d;
  }
  int calls = 0;
};

TEST(MultiStepTurn, AStepWithoutActionsCannotContinueTheTurn) {
  common::VirtualRuntime rt;
  FakeLink link;
  auto agent = std::make_unique<EmptyContinuingAgent>();
  EmptyContinuingAgent& seen = *agent;
  ConversationNode conversation(two_turns(), std::move(agent));
  rt.add(link);
  rt.add(conversation);
  rt.run_until(30'000'000);
  EXPECT_EQ(seen.calls, 1);
  ASSERT_EQ(conversation.turns().size(), 2u);
  EXPECT_EQ(conversation.turns()[0].intent, "idle");
  EXPECT_TRUE(conversation.finished());
}

}  // namespace
}  // namespace a3::agent
