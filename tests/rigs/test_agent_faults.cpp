// Faults inside the agent read from its dialogue (rigs/outputs/agent_faults.hpp): a refused
// command sent again unchanged, a timed-out command never sent again; and what is not a fault.
#include <gtest/gtest.h>

#include "rigs/outputs/agent_faults.hpp"

namespace a3::rigs {
namespace {

using nlohmann::json;

json mcp(const std::string& name, json args = json::object()) { return {{"type", "mcp"}, {"name", name}, {"args", args}}; }
json answered(const std::string& name, const std::string& status) { return {{"tool", name}, {"result", {{"status", status}}}}; }

json agent_turn(int turn, json actions, json obs) {
  return {{"turn", turn}, {"speaker", "agent"}, {"actions", std::move(actions)}, {"obs", std::move(obs)}};
}
json user_turn(int turn) { return {{"turn", turn}, {"speaker", "user"}, {"actions", json::array()}, {"obs", json::array()}}; }

const json kLegHome = mcp("navigate_to", {{"waypoints", {{0, 0, 30}}}});
const json kLegAround = mcp("navigate_to", {{"waypoints", {{50, 0, 30}, {0, 0, 30}}}});

TEST(AgentFaults, ARefusedCommandSentAgainUnchangedIsAFault) {
  const json dialogue = {agent_turn(1, {kLegHome}, {answered("navigate_to", "refused")}), user_turn(2),
                         agent_turn(3, {kLegHome}, {answered("navigate_to", "refused")}), user_turn(4),
                         agent_turn(5, {kLegHome}, {answered("navigate_to", "refused")})};
  const json faults = find_agent_faults(dialogue);
  ASSERT_EQ(faults.size(), 1u) << faults.dump();  // one per command, however often repeated
  EXPECT_EQ(faults[0]["kind"], "refused_repeated");
  EXPECT_EQ(faults[0]["turn"], 3);
  EXPECT_NE(faults[0]["detail"].get<std::string>().find("first refused at turn 1"), std::string::npos);
}

TEST(AgentFaults, ARefusalFollowedByAnotherPlanIsNot) {
  const json dialogue = {agent_turn(1, {kLegHome}, {answered("navigate_to", "refused")}), user_turn(2),
                         agent_turn(3, {kLegAround}, {answered("navigate_to", "accepted")})};
  EXPECT_TRUE(find_agent_faults(dialogue).empty());
}

TEST(AgentFaults, ATimedOutCommandNeverSentAgainIsAFault) {
  const json sensor = mcp("activate_sensor", {{"sensor", "thermal"}});
  const json dialogue = {agent_turn(1, {sensor}, {answered("activate_sensor", "timeout")}), user_turn(2),
                         agent_turn(3, {mcp("read_telemetry")}, {answered("read_telemetry", "ok")})};
  const json faults = find_agent_faults(dialogue);
  ASSERT_EQ(faults.size(), 1u) << faults.dump();
  EXPECT_EQ(faults[0]["kind"], "timeout_not_retried");
  EXPECT_EQ(faults[0]["turn"], 1);

  // Unanswered (no obs) counts as a timeout too.
  EXPECT_EQ(find_agent_faults(json{agent_turn(1, {sensor}, json::array()), agent_turn(3, json::array(), json::array())}).size(), 1u);
}

TEST(AgentFaults, TimeoutsThatAreNotFaults) {
  const json sensor = mcp("activate_sensor", {{"sensor", "thermal"}});
  // Sent again: recovered.
  EXPECT_TRUE(find_agent_faults(json{agent_turn(1, {sensor}, {answered("activate_sensor", "timeout")}),
                                     agent_turn(3, {sensor}, {answered("activate_sensor", "ok")})})
                  .empty());
  // In the agent's last turn: no turn was left to retry in.
  EXPECT_TRUE(find_agent_faults(json{agent_turn(1, {mcp("read_telemetry")}, {answered("read_telemetry", "ok")}),
                                     agent_turn(3, {sensor}, {answered("activate_sensor", "timeout")})})
                  .empty());
  // A lost take-off followed by a leg the vehicle accepted: the vehicle did take off.
  EXPECT_TRUE(find_agent_faults(json{agent_turn(1, {mcp("takeoff", {{"altitude_m", 30}}), kLegHome},
                                                {answered("takeoff", "timeout"), answered("navigate_to", "accepted")}),
                                     agent_turn(3, {mcp("read_telemetry")}, {answered("read_telemetry", "ok")})})
                  .empty());
  // A query (it changes nothing) need not be repeated.
  EXPECT_TRUE(find_agent_faults(json{agent_turn(1, {mcp("read_telemetry")}, {answered("read_telemetry", "timeout")}),
                                     agent_turn(3, json::array(), json::array())})
                  .empty());
}

TEST(AgentFaults, ADialogueOfAnotherShapeGivesNoFaultsRatherThanAnError) {
  EXPECT_TRUE(find_agent_faults(json::object()).empty());
  EXPECT_TRUE(find_agent_faults(json{{{"speaker", "agent"}, {"turn", 1}, {"actions", "x"}}}).empty());
}

}  // namespace
}  // namespace a3::rigs
