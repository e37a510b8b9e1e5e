// The vehicle's tool handlers registered by catalog name: the registry's own rules, the check of
// the catalog against the handlers both ways when the tool server is built, and the dispatch of
// every built-in catalog entry to the handler registered under its name.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>

#include "agent/tool_catalog.hpp"
#include "tests/vehicle/vehicle_test_util.hpp"
#include "vehicle/tool_handlers.hpp"
#include "vehicle/tool_server_node.hpp"
#include "vehicle/vehicle_tools.hpp"

namespace a3::vehicle {
namespace {

// The what() of the std::invalid_argument that building a tool server throws, or "".
std::string construction_error(const ToolCatalog& catalog, const ToolHandlers& handlers = vehicle_tools()) {
  try {
    ToolServerNode node(test::test_config(), catalog, handlers);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

nlohmann::json builtin_catalog_json() { return ToolCatalog::builtin().json(); }

// The built-in catalog's JSON with the named entry of a section ("mcp" by name, "a2a" by task)
// removed.
nlohmann::json without(const std::string& section, const std::string& key, const std::string& name) {
  nlohmann::json j = builtin_catalog_json();
  nlohmann::json kept = nlohmann::json::array();
  for (const auto& entry : j[section]) {
    if (entry.at(key) != name) kept.push_back(entry);
  }
  EXPECT_EQ(kept.size() + 1, j[section].size()) << name << " is not in the built-in catalog's " << section;
  j[section] = kept;
  return j;
}

// A value that satisfies a (simple) JSON Schema: each required property from its own schema.
nlohmann::json minimal_instance(const nlohmann::json& schema) {
  if (schema.contains("enum")) return schema["enum"][0];
  const std::string type = schema.value("type", std::string("object"));
  if (type == "number" || type == "integer") {
    if (schema.contains("minimum")) return schema["minimum"];
    if (schema.contains("exclusiveMinimum")) return schema["exclusiveMinimum"].get<double>() + 1.0;
    return 1.0;
  }
  if (type == "string") return "rgb";
  if (type == "boolean") return true;
  if (type == "array") {
    nlohmann::json a = nlohmann::json::array();
    const nlohmann::json items = schema.value("items", nlohmann::json::object());
    for (int i = 0; i < schema.value("minItems", 0); ++i) a.push_back(minimal_instance(items));
    return a;
  }
  nlohmann::json o = nlohmann::json::object();
  for (const auto& name : schema.value("required", nlohmann::json::array())) {
    o[name.get<std::string>()] = minimal_instance(schema["properties"][name.get<std::string>()]);
  }
  return o;
}

// Handlers for every entry of the catalog that answer with the name they were registered under.
ToolHandlers recording_handlers(const ToolCatalog& catalog) {
  ToolHandlers h;
  for (const auto& tool : catalog.tools()) {
    h.add_tool(tool.name, [name = tool.name](VehicleServices& vehicle, const nlohmann::json& args) {
      vehicle.finish_mcp({{"handled_by", name}, {"args", args}});
    });
  }
  for (const auto& task : catalog.tasks()) {
    h.add_task(task.task, [name = task.task](VehicleServices&, const nlohmann::json& payload) {
      PeerAnswer answer;
      answer.payload = {{"handled_by", name}, {"payload", payload}};
      return answer;
    });
  }
  return h;
}

TEST(ToolHandlers, TheBuiltInHandlersMatchTheBuiltInCatalogExactly) {
  const ToolCatalog& catalog = ToolCatalog::builtin();
  EXPECT_NO_THROW(vehicle_tools().check_against(catalog));
  EXPECT_EQ(vehicle_tools().tool_count(), catalog.tools().size());
  EXPECT_EQ(vehicle_tools().task_count(), catalog.tasks().size());
  for (const auto& tool : catalog.tools()) EXPECT_NE(vehicle_tools().find_tool(tool.name), nullptr) << tool.name;
  for (const auto& task : catalog.tasks()) EXPECT_NE(vehicle_tools().find_task(task.task), nullptr) << task.task;
  // report_turn ends the agent's turn and never reaches the vehicle: no handler.
  EXPECT_EQ(vehicle_tools().find_tool(catalog.turn_call().name), nullptr);
}

TEST(ToolHandlers, ANameRegisteredTwiceOrEmptyIsRefused) {
  ToolHandlers h;
  const ToolHandler noop = [](VehicleServices&, const nlohmann::json&) {};
  h.add_tool("hover", noop);
  try {
    h.add_tool("hover", noop);
    FAIL() << "a second handler for 'hover' was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'hover': registered twice"), std::string::npos) << e.what();
  }
  EXPECT_THROW(h.add_tool("", noop), std::invalid_argument);
  EXPECT_THROW(h.add_task("relay", TaskHandler()), std::invalid_argument);
}

TEST(ToolServerHandlers, ACatalogToolWithoutAHandlerStopsTheServerBeingBuilt) {
  nlohmann::json j = builtin_catalog_json();
  j["mcp"].push_back({{"name", "spray_crops"},
                      {"kind", "sensor"},
                      {"description", "Spray the field below."},
                      {"args", {{"type", "object"}}}});
  const ToolCatalog catalog(j);
  EXPECT_EQ(construction_error(catalog), "tool catalog: MCP tool 'spray_crops' has no handler on the vehicle");
}

TEST(ToolServerHandlers, ACatalogTaskWithoutAHandlerStopsTheServerBeingBuilt) {
  nlohmann::json j = builtin_catalog_json();
  j["a2a"].push_back({{"task", "relay_message"},
                      {"to", "ground_station"},
                      {"description", "Relay a message."},
                      {"payload", {{"type", "object"}}}});
  const ToolCatalog catalog(j);
  EXPECT_EQ(construction_error(catalog), "tool catalog: A2A task 'relay_message' has no handler on the vehicle");
}

TEST(ToolServerHandlers, AToolHandlerWithoutACatalogEntryStopsTheServerBeingBuilt) {
  const ToolCatalog catalog(without("mcp", "name", "hold"));
  EXPECT_EQ(construction_error(catalog),
            "vehicle tool handler 'hold' has no entry in the tool catalog's \"mcp\" section");
}

TEST(ToolServerHandlers, ATaskHandlerWithoutACatalogEntryStopsTheServerBeingBuilt) {
  const ToolCatalog catalog(without("a2a", "task", "path_plan"));
  EXPECT_EQ(construction_error(catalog),
            "vehicle task handler 'path_plan' has no entry in the tool catalog's \"a2a\" section");
}

TEST(ToolServerHandlers, TheBuiltInCatalogAndHandlersBuildAServer) {
  EXPECT_EQ(construction_error(ToolCatalog::builtin()), "");
}

// A tool server with the given handlers and a probe on the link; no flight controller.
struct HandlerRig {
  explicit HandlerRig(const ToolHandlers& handlers)
      : server(test::test_config(), ToolCatalog::builtin(), handlers), probe(test::SliceResponder::kSilent) {
    rt.add(server);
    rt.add(probe);
  }
  nlohmann::json call(const nlohmann::json& action) {
    const std::size_t before = probe.down.size();
    rt.bus().publish(common::channels::kLinkUpRx.of(0),
                     agent::encode_action(ActionEnvelope{turn, 0, action}, turn, rt.clock().now_us(), "agent"));
    ++turn;
    rt.run_until(rt.clock().now_us() + 100'000);
    if (probe.down.size() != before + 1) {
      ADD_FAILURE() << "expected one observation for " << action.dump() << ", got " << probe.down.size() - before;
      return nlohmann::json::object();
    }
    return probe.down.back().obs;
  }
  common::VirtualRuntime rt;
  ToolServerNode server;
  test::Probe probe;
  int turn = 1;
};

TEST(ToolServerHandlers, EveryBuiltInToolIsDispatchedToTheHandlerRegisteredUnderItsName) {
  const ToolCatalog& catalog = ToolCatalog::builtin();
  HandlerRig rig(recording_handlers(catalog));
  for (const auto& tool : catalog.tools()) {
    const nlohmann::json args = minimal_instance(tool.args_schema);
    const nlohmann::json obs = rig.call(test::mcp(tool.name, args));
    EXPECT_EQ(obs.value("tool", ""), tool.name) << obs.dump();
    EXPECT_EQ(obs["result"].value("handled_by", ""), tool.name) << obs.dump();
    EXPECT_EQ(obs["result"]["args"], args) << obs.dump();
  }
  EXPECT_EQ(rig.server.counters().get("mcp_calls"), catalog.tools().size());
  EXPECT_EQ(rig.server.counters().get("errors"), 0u);
}

TEST(ToolServerHandlers, EveryBuiltInTaskIsDispatchedToTheHandlerRegisteredUnderItsName) {
  const ToolCatalog& catalog = ToolCatalog::builtin();
  HandlerRig rig(recording_handlers(catalog));
  for (const auto& task : catalog.tasks()) {
    const nlohmann::json payload = minimal_instance(task.payload_schema);
    const nlohmann::json obs = rig.call(test::a2a(task.task, task.to, payload));
    EXPECT_EQ(obs.value("task", ""), task.task) << obs.dump();
    EXPECT_EQ(obs.value("from", ""), task.to) << obs.dump();
    EXPECT_EQ(obs.value("status", ""), "ok") << obs.dump();
    EXPECT_EQ(obs["payload"].value("handled_by", ""), task.task) << obs.dump();
  }
  EXPECT_EQ(rig.server.counters().get("a2a_messages"), catalog.tasks().size());
}

TEST(ToolServerHandlers, ArgumentsAgainstTheSchemaNeverReachTheHandler) {
  HandlerRig rig(recording_handlers(ToolCatalog::builtin()));
  const nlohmann::json obs = rig.call(test::mcp("takeoff", {{"altitude_m", -5.0}}));
  EXPECT_EQ(obs["result"].value("status", ""), "error") << obs.dump();
  EXPECT_FALSE(obs["result"].contains("handled_by")) << obs.dump();
}

}  // namespace
}  // namespace a3::vehicle
