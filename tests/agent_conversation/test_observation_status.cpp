// One reading of what an observation answered (turn.hpp): an MCP tool's result.status, an A2A
// answer's status, "timeout" for the conversation's stand-in for a lost answer or none at all,
// "" for an answer without a status.
#include <gtest/gtest.h>

#include "agent/conversation/turn.hpp"

namespace a3::agent {
namespace {

using nlohmann::json;

TEST(ObservationStatus, McpAndA2aAnswers) {
  EXPECT_EQ(observation_status({{"tool", "takeoff"}, {"result", {{"status", "accepted"}}}}), "accepted");
  EXPECT_EQ(observation_status({{"task", "path_plan"}, {"from", "ground_station"}, {"status", "ok"}}), "ok");
  EXPECT_EQ(observation_status({{"tool", "read_telemetry"}, {"result", {{"mode", "hold"}}}}), "");
}

TEST(ObservationStatus, LostOrMissingIsATimeout) {
  EXPECT_EQ(observation_status({{"tool", "takeoff"}, {"result", {{"status", "timeout"}}}}), "timeout");
  EXPECT_EQ(observation_status(json()), "timeout");
  EXPECT_EQ(observation_status(json::array()), "timeout");
  EXPECT_EQ(observation_status({{"tool", "takeoff"}, {"result", "text"}}), "timeout");
  Turn t;
  t.actions = json::array({{{"type", "mcp"}, {"name", "takeoff"}}, {{"type", "mcp"}, {"name", "land"}}});
  t.obs = json::array({{{"tool", "takeoff"}, {"result", {{"status", "accepted"}}}}});
  EXPECT_EQ(t.answer_status(0), "accepted");
  EXPECT_EQ(t.answer_status(1), "timeout");  // no observation for it
}

TEST(ObservationStatus, AStatusOfAnotherTypeIsNoStatus) {
  EXPECT_EQ(observation_status({{"tool", "x"}, {"result", {{"status", 3}}}}), "");
}

}  // namespace
}  // namespace a3::agent
