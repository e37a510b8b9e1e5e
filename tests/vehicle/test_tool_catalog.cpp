// The tool catalog: every MCP tool's schema accepts a good call and rejects bad ones naming
// the field; every A2A task's payload schema too; a catalog that is not one is refused.
#include <gtest/gtest.h>

#include <set>

#include "agent/tool_catalog.hpp"

namespace a3::agent {
namespace {

using nlohmann::json;

struct ToolCase {
  std::string tool;
  json good;
  std::vector<std::pair<json, std::string>> bad;  // arguments, the field the error must name
};

std::vector<ToolCase> tool_cases() {
  return {
      {"read_telemetry", {{"fields", {"pose", "battery_pct"}}}, {{{{"fields", "pose"}}, "args/fields"}, {{{"fields", {1}}}, "args/fields/0"}}},
      {"takeoff",
       {{"altitude_m", 30}},
       {{json::object(), "altitude_m"}, {{{"altitude_m", 0.5}}, "args/altitude_m"}, {{{"altitude_m", 501}}, "args/altitude_m"},
        {{{"altitude_m", "high"}}, "args/altitude_m"}}},
      {"set_waypoint",
       {{"x", 1}, {"y", -2.5}, {"z", 30}, {"speed_mps", 6}},
       {{{{"x", 1}, {"y", 2}}, "'z'"}, {{{"x", 1}, {"y", 2}, {"z", -1}}, "args/z"}, {{{"x", 1}, {"y", 2}, {"z", 3}, {"speed_mps", 0}}, "args/speed_mps"},
        {{{"x", true}, {"y", 2}, {"z", 3}}, "args/x"}, {{{"x", 1}, {"y", 2}, {"z", 3}, {"yaw", 4}}, "'yaw'"}}},
      {"navigate_to",
       {{"waypoints", {{1, 2, 30}, {4, 5, 30}}}, {"speed_mps", 5}},
       {{json::object(), "'waypoints'"}, {{{"waypoints", json::array()}}, "args/waypoints"},
        {{{"waypoints", {{1, 2, 3, 4}}}}, "args/waypoints/0"}, {{{"waypoints", {{1, "b", 3}}}}, "args/waypoints/0/1"}}},
      {"set_altitude", {{"z", 45}}, {{json::object(), "'z'"}, {{{"z", 1001}}, "args/z"}}},
      {"adjust_speed", {{"speed_mps", 8}}, {{{{"speed_mps", 26}}, "args/speed_mps"}, {{{"speed_mps", -1}}, "args/speed_mps"}}},
      {"execute_maneuver",
       {{"maneuver", "survey"}, {"area", {{0, 0}, {50, 0}, {50, 50}}}, {"spacing_m", 10}, {"z", 40}, {"capture", true}},
       {{json::object(), "'maneuver'"}, {{{"maneuver", "flip"}}, "args/maneuver"}, {{{"maneuver", "orbit"}, {"center", {1}}}, "args/center"},
        {{{"maneuver", "survey"}, {"spacing_m", 1}}, "args/spacing_m"}, {{{"maneuver", "orbit"}, {"radius_m", 0}}, "args/radius_m"},
        {{{"maneuver", "survey"}, {"capture", "yes"}}, "args/capture"}}},
      {"hold", json::object(), {{{{"seconds", 5}}, "'seconds'"}}},
      {"return_to_home", json::object(), {{{{"altitude_m", 50}}, "'altitude_m'"}}},
      {"land", json::object(), {{{{"x", 5}}, "'x'"}}},
      {"check_geofence", {{"x", 1}, {"y", 2}}, {{{{"x", "here"}}, "args/x"}}},
      {"activate_sensor", {{"sensor", "thermal"}, {"active", false}},
       {{json::object(), "'sensor'"}, {{{"sensor", ""}}, "args/sensor"}, {{{"sensor", "rgb"}, {"active", 1}}, "args/active"}}},
      {"capture_image", {{"sensor", "rgb"}, {"store_only", true}}, {{{{"sensor", 3}}, "args/sensor"}, {{{"store_only", "no"}}, "args/store_only"}}},
      {"switch_network_slice", {{"slice", "URLLC"}}, {{json::object(), "'slice'"}, {{{"slice", "6G"}}, "args/slice"}}},
  };
}

TEST(ToolCatalog, EveryToolAcceptsAGoodCallAndRejectsBadOnesNamingTheField) {
  const auto& catalog = ToolCatalog::builtin();
  const auto cases = tool_cases();
  std::set<std::string> covered;
  for (const auto& c : cases) {
    const McpToolSpec* tool = catalog.find_tool(c.tool);
    ASSERT_NE(tool, nullptr) << c.tool;
    covered.insert(c.tool);
    EXPECT_EQ(catalog.check_args(*tool, c.good), "") << c.tool << " " << c.good.dump();
    for (const auto& [args, field] : c.bad) {
      const std::string problem = catalog.check_args(*tool, args);
      EXPECT_NE(problem, "") << c.tool << " accepted " << args.dump();
      EXPECT_NE(problem.find(field), std::string::npos) << c.tool << " " << args.dump() << ": " << problem;
    }
  }
  EXPECT_EQ(covered.size(), catalog.tools().size()) << "a tool without a case";
  EXPECT_EQ(catalog.tools().size(), 14u);
}

TEST(ToolCatalog, ToolsAreFoundByNameAndHaveAKind) {
  const auto& catalog = ToolCatalog::builtin();
  EXPECT_EQ(catalog.find_tool("teleport"), nullptr);
  const std::set<std::string> kinds = {"query", "motion", "sensor", "network"};
  for (const auto& t : catalog.tools()) {
    EXPECT_EQ(kinds.count(t.kind), 1u) << t.name << ": " << t.kind;
    EXPECT_FALSE(t.description.empty()) << t.name;
  }
  EXPECT_EQ(catalog.find_tool("set_waypoint")->kind, "motion");
  EXPECT_EQ(catalog.find_tool("switch_network_slice")->kind, "network");
}

TEST(ToolCatalog, EveryTaskHasItsPeerAndChecksItsPayload) {
  const auto& catalog = ToolCatalog::builtin();
  const std::map<std::string, std::string> peers = {
      {"collision_avoidance", "uav_swarm_agent"}, {"swarm_status_check", "uav_swarm_agent"},
      {"swarm_formation", "uav_swarm_agent"},     {"request_weather_update", "weather_service"},
      {"path_plan", "ground_station"},            {"handover_data", "ground_station"}};
  EXPECT_EQ(catalog.tasks().size(), peers.size());
  for (const auto& [task, to] : peers) {
    const A2aTaskSpec* spec = catalog.find_task(task);
    ASSERT_NE(spec, nullptr) << task;
    EXPECT_EQ(spec->to, to);
    EXPECT_EQ(catalog.check_payload(*spec, json::object()), "") << task;
    const std::string problem = catalog.check_payload(*spec, json::array({1}));
    EXPECT_NE(problem.find("payload"), std::string::npos) << task << ": " << problem;
  }
  const auto& ca = *catalog.find_task("collision_avoidance");
  EXPECT_EQ(catalog.check_payload(ca, {{"request", "yield"}, {"pose", {{"x", 1}}}}), "");
  EXPECT_NE(catalog.check_payload(ca, {{"request", "dance"}}).find("payload/request"), std::string::npos);
  EXPECT_NE(catalog.check_payload(*catalog.find_task("path_plan"), {{"z", "high"}}).find("payload/z"), std::string::npos);
  EXPECT_NE(catalog.check_payload(*catalog.find_task("handover_data"), {{"items", "all"}}).find("payload/items"),
            std::string::npos);
  EXPECT_EQ(catalog.find_task("telepathy"), nullptr);
}

TEST(ToolCatalog, ACatalogThatIsNotOneIsRefused) {
  EXPECT_THROW(ToolCatalog(json::array()), std::invalid_argument);
  EXPECT_THROW(ToolCatalog(json{{"mcp", json::array()}}), std::invalid_argument);
  try {
    ToolCatalog bad(json{{"mcp", {{{"kind", "query"}, {"description", "d"}}}}, {"a2a", json::array()}});
    ADD_FAILURE() << "a tool without a name was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'name'"), std::string::npos) << e.what();
  }
  const ToolCatalog small(json{{"mcp", {{{"name", "ping"}, {"kind", "query"}, {"description", "d"},
                                         {"args", {{"type", "object"}, {"required", {"n"}}}}}}},
                               {"a2a", json::array()}});
  ASSERT_NE(small.find_tool("ping"), nullptr);
  EXPECT_NE(small.check_args(*small.find_tool("ping"), json::object()).find("'n'"), std::string::npos);
}

// One registry: the OpenAI functions and the MCP tools are the catalog's entries, every A2A task
// under "a2a_<task>", and report_turn; a call maps back to the α³ action it stands for.
TEST(ToolCatalog, FunctionsListEveryToolTaskAndTheTurnCallOnce) {
  const auto& catalog = ToolCatalog::builtin();
  const json openai = catalog.openai_tools();
  const json mcp = catalog.mcp_tools();
  ASSERT_EQ(openai.size(), catalog.tools().size() + catalog.tasks().size() + 1);
  ASSERT_EQ(mcp.size(), openai.size());
  std::set<std::string> names;
  for (std::size_t i = 0; i < openai.size(); ++i) {
    EXPECT_EQ(openai[i]["type"], "function");
    const std::string name = openai[i]["function"]["name"];
    EXPECT_EQ(mcp[i]["name"], name);
    EXPECT_EQ(mcp[i]["inputSchema"]["type"], "object") << name;
    EXPECT_TRUE(names.insert(name).second) << name;
  }
  for (const auto& t : catalog.tools()) EXPECT_TRUE(names.count(t.name)) << t.name;
  for (const auto& t : catalog.tasks()) EXPECT_TRUE(names.count("a2a_" + t.task)) << t.task;
  EXPECT_TRUE(names.count("report_turn"));
}

TEST(ToolCatalog, ACallBecomesTheActionItStandsFor) {
  const auto& catalog = ToolCatalog::builtin();
  const CallAsAction takeoff = catalog.action_from_call("takeoff", "{\"altitude_m\": 30}");
  EXPECT_EQ(takeoff.problem, "");
  EXPECT_EQ(takeoff.action, (json{{"type", "mcp"}, {"name", "takeoff"}, {"args", {{"altitude_m", 30}}}}));
  EXPECT_EQ(ToolCatalog::function_name_of(takeoff.action), "takeoff");
  const CallAsAction weather = catalog.action_from_call("a2a_request_weather_update", "");
  EXPECT_EQ(weather.problem, "");
  EXPECT_EQ(weather.action["to"], "weather_service");
  EXPECT_EQ(ToolCatalog::function_name_of(weather.action), "a2a_request_weather_update");
  const CallAsAction report = catalog.action_from_call("report_turn", json{{"intent", "survey"}, {"text", "ok"}});
  EXPECT_TRUE(report.ends_turn);
  EXPECT_EQ(report.problem, "");
  EXPECT_NE(catalog.action_from_call("takeoff", "{\"altitude_m\": 0.1}").problem.find("args/altitude_m"), std::string::npos);
  EXPECT_NE(catalog.action_from_call("fly", "{}").problem.find("unknown function 'fly'"), std::string::npos);
  EXPECT_NE(catalog.action_from_call("hold", "{oops").problem.find("not JSON"), std::string::npos);
  EXPECT_NE(catalog.action_from_call("report_turn", json{{"text", "x"}}).problem.find("intent"), std::string::npos);
}

}  // namespace
}  // namespace a3::agent
