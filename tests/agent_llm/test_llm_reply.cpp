// Parsing a model's reply into an agent turn: good replies in every wrapping models use, and
// every kind of bad reply rejected with a problem naming its place, never an exception.
#include <gtest/gtest.h>

#include "agent/llm/json_extract.hpp"
#include "agent/llm/llm_reply.hpp"

namespace a3 {
namespace {

using agent::llm::parse_reply;
using agent::llm::ParsedReply;

const agent::ToolCatalog& tools() { return agent::ToolCatalog::builtin(); }

const char* kGood = R"({"intent": "arm_and_takeoff", "text": "Taking off to 60 m.", "actions": [
  {"type": "mcp", "name": "takeoff", "args": {"altitude_m": 60}},
  {"type": "a2a", "to": "weather_service", "task": "request_weather_update", "payload": {}},
  {"type": "mcp", "name": "read_telemetry"}]})";

void expect_good(const ParsedReply& r) {
  ASSERT_TRUE(r.ok()) << r.problems_text();
  EXPECT_EQ(r.intent, "arm_and_takeoff");
  EXPECT_EQ(r.text, "Taking off to 60 m.");
  ASSERT_EQ(r.actions.size(), 3u);
  EXPECT_EQ(r.actions[0], nlohmann::json::parse(R"({"type": "mcp", "name": "takeoff", "args": {"altitude_m": 60}})"));
  EXPECT_EQ(r.actions[1], nlohmann::json::parse(
                              R"({"type": "a2a", "task": "request_weather_update", "to": "weather_service", "payload": {}})"));
  // A tool without arguments gets {}.
  EXPECT_EQ(r.actions[2], nlohmann::json::parse(R"({"type": "mcp", "name": "read_telemetry", "args": {}})"));
}

// The single problem of a reply, which must contain `expected`.
void expect_problem(const std::string& reply, const std::string& expected) {
  ParsedReply r;
  ASSERT_NO_THROW(r = parse_reply(reply, tools()));
  EXPECT_FALSE(r.ok()) << reply;
  EXPECT_TRUE(r.actions.empty()) << "no actions from an unusable reply";
  EXPECT_NE(r.problems_text().find(expected), std::string::npos) << "problems: " << r.problems_text();
}

TEST(LlmReply, PlainJsonObject) { expect_good(parse_reply(kGood, tools())); }

TEST(LlmReply, FencedJson) {
  expect_good(parse_reply(std::string("```json\n") + kGood + "\n```", tools()));
  expect_good(parse_reply(std::string("```\n") + kGood + "\n```\n", tools()));
}

TEST(LlmReply, ProseAroundTheObject) {
  expect_good(parse_reply(std::string("Sure! Here is my next turn:\n") + kGood +
                              "\nLet me know if {anything} should change.",
                          tools()));
  // Braces in prose before the object, and inside its strings, do not confuse the extraction.
  const std::string tricky = R"(I'll use {x} notation. {"intent": "status_report", "text": "a } and a { in text", "actions": []})";
  const ParsedReply r = parse_reply(tricky, tools());
  ASSERT_TRUE(r.ok()) << r.problems_text();
  EXPECT_EQ(r.text, "a } and a { in text");
  EXPECT_TRUE(r.actions.empty());
}

TEST(LlmReply, NotJson) {
  expect_problem("I will take off now.", "reply: no JSON object in the reply");
  expect_problem("", "reply: empty");
  expect_problem("   \n", "reply: empty");
  expect_problem(R"({"intent": "x", "actions": [,]})", "byte 28: not valid JSON");
  expect_problem(R"({"intent": "x", "actions": [)", "never closed");
  expect_problem(R"(["intent", "x"])", "not an object");
  expect_problem("\xff\xfe{\"intent\": \"x\\xff\"}", "reply:");
  // Bytes that are not UTF-8: the problems (which go into JSON) stay valid UTF-8.
  const ParsedReply bad = parse_reply("{\"intent\": \"x\xff\xc3\", \"actions\": []}", tools());
  EXPECT_FALSE(bad.ok());
  EXPECT_NO_THROW(nlohmann::json(bad.problems).dump()) << bad.problems_text();
}

TEST(JsonExtract, ValidUtf8ReplacesOnlyBrokenBytes) {
  EXPECT_EQ(agent::llm::valid_utf8("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9a\x81"), "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9a\x81");
  EXPECT_EQ(agent::llm::valid_utf8("a\xff b\xc3 c\xed\xa0\x80 d\xe2\x82"),
            "a\xef\xbf\xbd b\xef\xbf\xbd c\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd d\xef\xbf\xbd\xef\xbf\xbd");
}

TEST(LlmReply, MissingOrBadIntent) {
  expect_problem(R"({"text": "hi", "actions": []})", "intent: missing");
  expect_problem(R"({"intent": "", "actions": []})", "intent: expected a non-empty string");
  expect_problem(R"({"intent": 3, "actions": []})", "intent: expected a non-empty string");
}

TEST(LlmReply, ActionsMustBeAnArray) {
  expect_problem(R"({"intent": "x"})", "actions: missing");
  expect_problem(R"({"intent": "x", "actions": {"type": "mcp"}})", "actions: expected an array, got object");
  expect_problem(R"({"intent": "x", "text": 5, "actions": []})", "text: expected a string");
  expect_problem(R"({"intent": "x", "actions": ["takeoff"]})", "actions/0: expected an object, got string");
  expect_problem(R"({"intent": "x", "actions": [{"name": "takeoff"}]})", "actions/0/type: missing");
  expect_problem(R"({"intent": "x", "actions": [{"type": "tool", "name": "takeoff"}]})",
                 "actions/0/type: expected \"mcp\" or \"a2a\", got \"tool\"");
}

TEST(LlmReply, UnknownTool) {
  expect_problem(R"({"intent": "x", "actions": [{"type": "mcp", "name": "read_telemetry"}, {"type": "mcp", "name": "fly_to", "args": {}}]})",
                 "actions/1/name: unknown tool 'fly_to' (known: read_telemetry, takeoff,");
  expect_problem(R"({"intent": "x", "actions": [{"type": "mcp", "args": {}}]})", "actions/0/name: missing");
}

TEST(LlmReply, ArgumentsAgainstTheSchema) {
  // z above the schema's maximum, in the third action.
  expect_problem(R"({"intent": "x", "actions": [{"type": "mcp", "name": "read_telemetry"},
      {"type": "mcp", "name": "adjust_speed", "args": {"speed_mps": 5}},
      {"type": "mcp", "name": "set_waypoint", "args": {"x": 1, "y": 2, "z": 5000}}]})",
                 "actions/2/args/z:");
  expect_problem(R"({"intent": "x", "actions": [{"type": "mcp", "name": "takeoff", "args": {}}]})", "actions/0/args");
  expect_problem(R"({"intent": "x", "actions": [{"type": "mcp", "name": "takeoff", "args": {"altitude_m": "high"}}]})",
                 "actions/0/args/altitude_m:");
  expect_problem(R"({"intent": "x", "actions": [{"type": "mcp", "name": "takeoff", "args": [60]}]})",
                 "actions/0/args: expected an object, got array");
  const ParsedReply two = parse_reply(
      R"({"intent": "x", "actions": [{"type": "mcp", "name": "set_waypoint", "args": {"x": "a", "y": 2, "z": -1}}]})", tools());
  EXPECT_GE(two.problems.size(), 2u) << two.problems_text();
  for (const auto& p : two.problems) EXPECT_EQ(p.rfind("actions/0/args", 0), 0u) << p;
}

TEST(LlmReply, UnknownA2aTaskOrWrongPeer) {
  expect_problem(R"({"intent": "x", "actions": [{"type": "a2a", "to": "uav_swarm_agent", "task": "fly_formation", "payload": {}}]})",
                 "actions/0/task: unknown A2A task 'fly_formation' (known: collision_avoidance,");
  expect_problem(R"({"intent": "x", "actions": [{"type": "a2a", "to": "uav_swarm_agent", "task": "path_plan", "payload": {}}]})",
                 "actions/0/to: task 'path_plan' goes to 'ground_station', not 'uav_swarm_agent'");
  expect_problem(R"({"intent": "x", "actions": [{"type": "a2a", "task": "path_plan", "payload": {}}]})",
                 "actions/0/to: missing (task 'path_plan' goes to 'ground_station')");
  expect_problem(R"({"intent": "x", "actions": [{"type": "a2a", "to": "uav_swarm_agent", "task": "collision_avoidance", "payload": {"request": "dance"}}]})",
                 "actions/0/payload/request:");
  expect_problem(R"({"intent": "x", "actions": [{"type": "a2a", "to": "ground_station", "task": "path_plan", "payload": "go"}]})",
                 "actions/0/payload: expected an object, got string");
}

TEST(LlmReply, EveryProblemIsReportedNotJustTheFirst) {
  const ParsedReply r = parse_reply(R"({"actions": [{"type": "mcp", "name": "nope"}, {"type": "a2a", "task": "nope2"}]})", tools());
  EXPECT_EQ(r.problems.size(), 3u) << r.problems_text();
}

TEST(JsonExtract, TopLevelSpansOnly) {
  const auto spans = agent::llm::top_level_object_spans(R"(a {"b": {"c": "}"}} d {"e": 1} {"f")");
  ASSERT_EQ(spans.size(), 3u);
  EXPECT_EQ(spans[0].begin, 2u);
  EXPECT_EQ(spans[0].end, 19u);
  EXPECT_TRUE(spans[1].closed);
  EXPECT_FALSE(spans[2].closed);
}

}  // namespace
}  // namespace a3
