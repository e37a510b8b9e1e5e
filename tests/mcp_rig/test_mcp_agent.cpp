// McpAgent alone, with the test as the conversation: a waiting call reports progress and
// names what it waits for; nothing blocks for ever (a torn-down conversation or the run's stop
// flag releases decide() and waiting calls); the end of the dialogue answers a pending
// report_turn and every later call; a client that leaves mid-dialogue stops the run, after the
// dialogue it does not; the client's wall time is charged only when asked.
#include <gtest/gtest.h>

#include <future>
#include <thread>

#include "agent/mcp/mcp_agent.hpp"

namespace a3::agent::mcp {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

McpMissionBrief brief() {
  McpMissionBrief b;
  b.scenario = "test";
  b.mission.description = "Fly a test.";
  b.max_turns = 4;
  return b;
}

McpAgentOptions options(std::atomic<bool>* stop, double progress_period_s = 1.0, bool charge = true) {
  McpAgentOptions o;
  o.stop = stop;
  o.progress_period_s = progress_period_s;
  o.charge_wall_time = charge;
  return o;
}

Turn user_turn(int number, const std::string& text) {
  Turn t;
  t.number = number;
  t.speaker = "user";
  t.intent = "instruct";
  t.text = text;
  return t;
}

TEST(McpAgent, AWaitingCallReportsProgressAndEndsWhenTheConversationIsTornDown) {
  std::atomic<bool> stop{false};
  McpAgent agent(brief(), options(&stop, 0.05));
  std::vector<std::string> messages;
  std::mutex m;
  auto call = std::async(std::launch::async, [&] {
    return agent.call_tool("read_telemetry", json::object(), [&](double, std::optional<double>, const std::string& s) {
      std::lock_guard<std::mutex> lock(m);
      messages.push_back(s);
    });
  });
  std::this_thread::sleep_for(300ms);
  agent.stop_deciding();
  ASSERT_EQ(call.wait_for(5s), std::future_status::ready);
  const McpCallResult r = call.get();
  EXPECT_TRUE(r.is_error);
  std::lock_guard<std::mutex> lock(m);
  ASSERT_GE(messages.size(), 2u);
  EXPECT_NE(messages[0].find("waiting for the agent's turn"), std::string::npos) << messages[0];
}

TEST(McpAgent, DecideReturnsWhenTheRunStops) {
  std::atomic<bool> stop{false};
  McpAgent agent(brief(), options(&stop));
  std::vector<Turn> dialogue;
  AgentContext c;
  c.dialogue = &dialogue;
  auto decision = std::async(std::launch::async, [&] { return agent.decide(c); });
  EXPECT_EQ(decision.wait_for(200ms), std::future_status::timeout);  // waits for a call
  stop = true;
  ASSERT_EQ(decision.wait_for(5s), std::future_status::ready);
  const AgentDecision d = decision.get();
  EXPECT_TRUE(d.actions.empty());
  EXPECT_FALSE(d.turn_continues);
}

TEST(McpAgent, AToolCallIsAContinuingStepAndItsObservationIsItsResult) {
  std::atomic<bool> stop{false};
  McpAgent agent(brief(), options(&stop, 1.0, false));
  std::vector<Turn> dialogue;
  AgentContext c;
  c.dialogue = &dialogue;
  auto call = std::async(std::launch::async, [&] {
    return agent.call_tool("takeoff", {{"altitude_m", 30}}, {});
  });
  const AgentDecision d = agent.decide(c);
  ASSERT_EQ(d.actions.size(), 1u);
  EXPECT_EQ(d.actions[0]["name"], "takeoff");
  EXPECT_TRUE(d.turn_continues);
  EXPECT_EQ(d.latency_s, 0.0);  // charge_wall_time off
  // The conversation's next step carries the observation: a refusal is an error result.
  c.step = 2;
  c.turn_actions = d.actions;
  c.turn_obs = json::array({{{"tool", "takeoff"}, {"result", {{"status", "refused"}, {"reason", "battery"}}}}});
  auto next = std::async(std::launch::async, [&] { return agent.decide(c); });
  const McpCallResult r = call.get();
  EXPECT_TRUE(r.is_error);
  EXPECT_EQ(r.structured.value("reason", ""), "battery");
  // End the turn so that the pending decide() returns.
  const McpCallResult reply_pending = [&] {
    auto report = std::async(std::launch::async, [&] {
      return agent.call_tool("report_turn", {{"intent", "abort"}, {"text", "Refused."}}, {});
    });
    const AgentDecision last = next.get();
    EXPECT_EQ(last.intent, "abort");
    EXPECT_FALSE(last.turn_continues);
    agent.on_dialogue({user_turn(2, "Understood, stop there.")}, true, "turn budget used");
    return report.get();
  }();
  EXPECT_FALSE(reply_pending.is_error);
  EXPECT_EQ(reply_pending.structured["text"], "Understood, stop there.");
  EXPECT_TRUE(reply_pending.structured["dialogue_over"].get<bool>());
  const McpCallResult after = agent.call_tool("read_telemetry", json::object(), {});
  EXPECT_TRUE(after.is_error);
  EXPECT_EQ(after.structured["status"], "dialogue_over");
  EXPECT_NE(after.text.find("turn budget used"), std::string::npos) << after.text;
}

TEST(McpAgent, ChargesTheClientsWallTimeWhenAsked) {
  std::atomic<bool> stop{false};
  McpAgent agent(brief(), options(&stop));
  std::vector<Turn> dialogue;
  AgentContext c;
  c.dialogue = &dialogue;
  auto call = std::async(std::launch::async, [&] {
    std::this_thread::sleep_for(250ms);
    return agent.call_tool("report_turn", {{"intent", "status"}, {"text", "Fine."}}, {});
  });
  const AgentDecision d = agent.decide(c);
  EXPECT_GE(d.latency_s, 0.25);
  EXPECT_LT(d.latency_s, 5.0);
  EXPECT_TRUE(d.actions.empty());
  dialogue.push_back(user_turn(2, "Carry on."));
  c.turn_number = 3;
  auto next = std::async(std::launch::async, [&] { return agent.decide(c); });
  EXPECT_EQ(call.get().structured["text"], "Carry on.");
  stop = true;
  next.get();
}

TEST(McpAgent, AClientLeavingStopsTheRunOnlyMidDialogue) {
  std::atomic<bool> stop{false};
  McpAgent mid(brief(), options(&stop));
  mid.client_closed();
  EXPECT_TRUE(stop.load());
  EXPECT_TRUE(mid.client_gone());

  std::atomic<bool> stop_after{false};
  McpAgent after(brief(), options(&stop_after));
  after.on_dialogue({user_turn(2, "Done.")}, true, "the vehicle has landed");
  after.client_closed();
  EXPECT_FALSE(stop_after.load());
  // The dialogue resource shows what the conversation last told the agent.
  const json dialogue = json::parse(*after.read_resource("a3rig://dialogue"));
  ASSERT_EQ(dialogue["turns"].size(), 1u);
  EXPECT_EQ(dialogue["turns"][0]["text"], "Done.");
  EXPECT_TRUE(dialogue["over"].get<bool>());
}

TEST(McpAgent, BadCallsAnswerAtOnceNamingTheProblem) {
  std::atomic<bool> stop{false};
  McpAgent agent(brief(), options(&stop));
  const McpCallResult unknown = agent.call_tool("fly_to_the_moon", json::object(), {});
  EXPECT_TRUE(unknown.is_error);
  EXPECT_NE(unknown.text.find("fly_to_the_moon"), std::string::npos) << unknown.text;
  const McpCallResult bad = agent.call_tool("set_waypoint", {{"x", 1}}, {});
  EXPECT_TRUE(bad.is_error);
  EXPECT_NE(bad.text.find("set_waypoint"), std::string::npos) << bad.text;
  EXPECT_TRUE(agent.read_resource("a3rig://mission").has_value());
  EXPECT_NE(agent.read_resource("a3rig://mission")->find("Fly a test."), std::string::npos);
  EXPECT_FALSE(agent.read_resource("a3rig://nothing").has_value());
}

}  // namespace
}  // namespace a3::agent::mcp
