// The MCP session's methods and JSON-RPC errors, transport-free, against a fake rig.
#include "agent/mcp/mcp_protocol.hpp"
#include "tests/mcp_protocol/fake_mcp_rig.hpp"
#include "tests/mcp_protocol/message_sink.hpp"

#include <gtest/gtest.h>

#include <map>

namespace a3::agent::mcp {
namespace {

using nlohmann::json;
using testing::FakeMcpRig;
using testing::MessageSink;

json request(int id, const std::string& method, json params = json::object()) {
  return json{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", std::move(params)}};
}

json call(int id, const std::string& name, json arguments = json::object(), json meta = nullptr) {
  json params{{"name", name}, {"arguments", std::move(arguments)}};
  if (!meta.is_null()) params["_meta"] = std::move(meta);
  return request(id, "tools/call", std::move(params));
}

class McpProtocolTest : public ::testing::Test {
 protected:
  // One request's one response (synchronous methods, or waiting for a call).
  json ask(const json& message) {
    MessageSink sink;
    EXPECT_TRUE(protocol.handle(message, std::ref(sink)));
    return sink.wait_for(1).at(0);
  }
  json initialize(const std::string& version = "2025-06-18") {
    json reply = ask(request(0, "initialize", {{"protocolVersion", version}, {"capabilities", json::object()},
                                               {"clientInfo", {{"name", "test"}, {"version", "1"}}}}));
    MessageSink sink;
    EXPECT_FALSE(protocol.handle(json{{"jsonrpc", "2.0"}, {"method", "notifications/initialized"}}, std::ref(sink)));
    return reply;
  }

  FakeMcpRig rig;
  std::vector<std::string> log_lines;
  McpProtocol protocol{rig, [this](const std::string& line) { log_lines.push_back(line); }};
};

TEST_F(McpProtocolTest, InitializeAnswersTheRequestedSupportedVersionWithCapabilitiesAndTheBrief) {
  const json reply = initialize("2025-06-18");
  EXPECT_EQ(reply["id"], 0);
  EXPECT_EQ(reply["result"]["protocolVersion"], "2025-06-18");
  EXPECT_TRUE(reply["result"]["capabilities"].contains("tools"));
  EXPECT_TRUE(reply["result"]["capabilities"].contains("resources"));
  EXPECT_EQ(reply["result"]["serverInfo"]["name"], "fake-rig");
  EXPECT_EQ(reply["result"]["serverInfo"]["version"], "0.0.1");
  EXPECT_EQ(reply["result"]["instructions"], "Fly to the survey area and land.");
  EXPECT_EQ(protocol.protocol_version(), "2025-06-18");
}

TEST_F(McpProtocolTest, InitializeAccepts20250326) {
  EXPECT_EQ(initialize("2025-03-26")["result"]["protocolVersion"], "2025-03-26");
}

TEST_F(McpProtocolTest, InitializeWithAnUnknownVersionIsOfferedTheLatest) {
  EXPECT_EQ(initialize("2024-11-05")["result"]["protocolVersion"], "2025-06-18");
}

TEST_F(McpProtocolTest, InitializeWithoutAVersionIsInvalidParams) {
  const json reply = ask(request(1, "initialize", json::object()));
  EXPECT_EQ(reply["error"]["code"], -32602);
  EXPECT_NE(reply["error"]["message"].get<std::string>().find("protocolVersion"), std::string::npos);
}

TEST_F(McpProtocolTest, ASecondInitializeIsRefused) {
  initialize();
  EXPECT_EQ(ask(request(5, "initialize", {{"protocolVersion", "2025-06-18"}}))["error"]["code"], -32600);
}

TEST_F(McpProtocolTest, MethodsBeforeInitializeAreRefusedButPingIsAnswered) {
  EXPECT_EQ(ask(request(1, "tools/list"))["error"]["code"], -32600);
  EXPECT_EQ(ask(request(2, "ping"))["result"], json::object());
}

TEST_F(McpProtocolTest, PingAnswersAnEmptyResult) {
  initialize();
  const json reply = ask(request(7, "ping"));
  EXPECT_EQ(reply, json({{"jsonrpc", "2.0"}, {"id", 7}, {"result", json::object()}}));
}

TEST_F(McpProtocolTest, ToolsListIsTheRigsTools) {
  initialize();
  const json tools = ask(request(1, "tools/list"))["result"]["tools"];
  ASSERT_EQ(tools.size(), 3u);
  EXPECT_EQ(tools[0]["name"], "read_telemetry");
  EXPECT_EQ(tools[0]["inputSchema"]["type"], "object");
}

TEST_F(McpProtocolTest, ToolsCallCarriesTextStructuredContentAndIsError) {
  initialize();
  const json result = ask(call(3, "read_telemetry"))["result"];
  EXPECT_EQ(result["structuredContent"]["altitude_m"], 12.5);
  EXPECT_EQ(result["content"][0]["type"], "text");
  EXPECT_EQ(json::parse(result["content"][0]["text"].get<std::string>())["altitude_m"], 12.5);
  EXPECT_EQ(result["isError"], false);
  const json said = ask(call(4, "report_turn", {{"intent", "done"}, {"text", "landed"}}))["result"];
  EXPECT_EQ(said["content"][0]["text"], "carry on");
}

TEST_F(McpProtocolTest, ARefusalIsAnIsErrorResult) {
  initialize();
  rig.release();
  const json result = ask(call(3, "fly_to", {{"refuse", true}}))["result"];
  EXPECT_EQ(result["isError"], true);
  EXPECT_EQ(result["content"][0]["text"], "refused: geofence");
}

TEST_F(McpProtocolTest, AnUnknownToolIsInvalidParamsNamingIt) {
  initialize();
  const json reply = ask(call(3, "self_destruct"));
  EXPECT_EQ(reply["error"]["code"], -32602);
  EXPECT_NE(reply["error"]["message"].get<std::string>().find("self_destruct"), std::string::npos);
  EXPECT_TRUE(rig.call_log().empty());
}

TEST_F(McpProtocolTest, ArgumentsThatAreNotAnObjectAreInvalidParams) {
  initialize();
  EXPECT_EQ(ask(request(3, "tools/call", {{"name", "read_telemetry"}, {"arguments", 5}}))["error"]["code"], -32602);
  EXPECT_EQ(ask(request(4, "tools/call", {{"arguments", json::object()}}))["error"]["code"], -32602);
}

TEST_F(McpProtocolTest, ARigExceptionIsAnInternalErrorNamingTheTool) {
  initialize();
  const json reply = ask(call(3, "read_telemetry", {{"fail", true}}));
  EXPECT_EQ(reply["error"]["code"], -32603);
  EXPECT_NE(reply["error"]["message"].get<std::string>().find("telemetry bus down"), std::string::npos);
}

TEST_F(McpProtocolTest, AnUnknownMethodIsMethodNotFound) {
  initialize();
  const json reply = ask(request(9, "sampling/createMessage"));
  EXPECT_EQ(reply["error"]["code"], -32601);
  EXPECT_EQ(reply["id"], 9);
}

TEST_F(McpProtocolTest, MalformedMessagesAreInvalidRequests) {
  EXPECT_EQ(ask(json{{"id", 1}, {"method", "ping"}})["error"]["code"], -32600);           // no jsonrpc
  EXPECT_EQ(ask(json{{"jsonrpc", "2.0"}, {"id", 1}, {"method", 3}})["error"]["code"], -32600);
  EXPECT_EQ(ask(json{{"jsonrpc", "2.0"}, {"id", 1.5}, {"method", "ping"}})["error"]["code"], -32600);
  EXPECT_EQ(ask(json("hello"))["error"]["code"], -32600);
}

TEST_F(McpProtocolTest, UnparseableTextIsAParseErrorWithANullId) {
  MessageSink sink;
  EXPECT_TRUE(protocol.handle_text("{\"jsonrpc\": \"2.0\", ", std::ref(sink)));
  const json reply = sink.all().at(0);
  EXPECT_EQ(reply["error"]["code"], -32700);
  EXPECT_TRUE(reply["id"].is_null());
}

TEST_F(McpProtocolTest, NotificationsAndResponsesGetNoAnswer) {
  initialize();
  MessageSink sink;
  EXPECT_FALSE(protocol.handle(json{{"jsonrpc", "2.0"}, {"method", "notifications/cancelled"},
                                    {"params", {{"requestId", 4}, {"reason", "user"}}}}, std::ref(sink)));
  EXPECT_FALSE(protocol.handle(json{{"jsonrpc", "2.0"}, {"id", 1}, {"result", json::object()}}, std::ref(sink)));
  EXPECT_TRUE(sink.all().empty());
  ASSERT_FALSE(log_lines.empty());
  EXPECT_NE(log_lines.front().find("cancelled request 4"), std::string::npos);
}

TEST_F(McpProtocolTest, ResourcesListAndRead) {
  initialize();
  const json list = ask(request(1, "resources/list"))["result"]["resources"];
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["uri"], "a3rig://mission");
  EXPECT_EQ(list[0]["mimeType"], "application/json");
  const json contents = ask(request(2, "resources/read", {{"uri", "a3rig://mission"}}))["result"]["contents"];
  EXPECT_EQ(contents[0]["text"], R"({"objective":"survey"})");
  EXPECT_EQ(contents[0]["mimeType"], "application/json");
}

TEST_F(McpProtocolTest, ReadingAnUnknownResourceIsResourceNotFound) {
  initialize();
  const json reply = ask(request(2, "resources/read", {{"uri", "a3rig://nope"}}));
  EXPECT_EQ(reply["error"]["code"], -32002);
  EXPECT_NE(reply["error"]["message"].get<std::string>().find("a3rig://nope"), std::string::npos);
}

TEST_F(McpProtocolTest, ProgressNotificationsPrecedeTheResponseWhenAsked) {
  initialize();
  MessageSink sink;
  ASSERT_TRUE(protocol.handle(call(5, "fly_to", json::object(), {{"progressToken", "tok"}}), std::ref(sink)));
  ASSERT_TRUE(rig.wait_for_flying(std::chrono::seconds(10)));
  rig.release();
  const auto messages = sink.wait_for(3);
  ASSERT_EQ(messages.size(), 3u);  // the non-rising 0.5 was dropped
  EXPECT_EQ(messages[0]["method"], "notifications/progress");
  EXPECT_EQ(messages[0]["params"], json({{"progressToken", "tok"}, {"progress", 0.5}, {"total", 1.0}, {"message", "halfway"}}));
  EXPECT_EQ(messages[1]["params"]["progress"], 1.0);
  EXPECT_FALSE(messages[1]["params"].contains("message"));
  EXPECT_EQ(messages[2]["id"], 5);
  EXPECT_EQ(messages[2]["result"]["structuredContent"]["arrived"], true);
}

TEST_F(McpProtocolTest, NoProgressWithoutAToken) {
  initialize();
  rig.release();
  MessageSink sink;
  ASSERT_TRUE(protocol.handle(call(5, "fly_to"), std::ref(sink)));
  const auto messages = sink.wait_for(1);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0]["id"], 5);
}

TEST_F(McpProtocolTest, PingIsAnsweredWhileACallBlocks) {
  initialize();
  MessageSink call_sink;
  ASSERT_TRUE(protocol.handle(call(5, "fly_to"), std::ref(call_sink)));
  ASSERT_TRUE(rig.wait_for_flying(std::chrono::seconds(10)));
  EXPECT_EQ(ask(request(6, "ping"))["id"], 6);
  EXPECT_EQ(ask(request(7, "tools/list"))["result"]["tools"].size(), 3u);
  EXPECT_TRUE(call_sink.all().empty());
  rig.release();
  EXPECT_EQ(call_sink.wait_for(1).at(0)["id"], 5);
}

TEST_F(McpProtocolTest, CallsRunOneAtATimeInArrivalOrder) {
  initialize();
  MessageSink sink;
  protocol.handle(call(1, "fly_to"), std::ref(sink));
  protocol.handle(call(2, "read_telemetry"), std::ref(sink));
  protocol.handle(call(3, "report_turn"), std::ref(sink));
  ASSERT_TRUE(rig.wait_for_flying(std::chrono::seconds(10)));
  EXPECT_EQ(rig.call_log(), std::vector<std::string>{"fly_to"});
  rig.release();
  const auto messages = sink.wait_for(3);
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_EQ(messages[0]["id"], 1);
  EXPECT_EQ(messages[1]["id"], 2);
  EXPECT_EQ(messages[2]["id"], 3);
  EXPECT_EQ(rig.call_log(), (std::vector<std::string>{"fly_to", "read_telemetry", "report_turn"}));
}

TEST_F(McpProtocolTest, ABatchIsAnsweredAsOneArrayIn20250326) {
  initialize("2025-03-26");
  MessageSink sink;
  const json batch = json::array({request(1, "ping"), call(2, "read_telemetry"),
                                  json{{"jsonrpc", "2.0"}, {"method", "notifications/initialized"}},
                                  request(3, "no/such")});
  ASSERT_TRUE(protocol.handle(batch, std::ref(sink)));
  const json replies = sink.wait_for(1).at(0);
  ASSERT_TRUE(replies.is_array());
  ASSERT_EQ(replies.size(), 3u);
  std::map<int, json> by_id;
  for (const auto& reply : replies) by_id[reply["id"].get<int>()] = reply;
  EXPECT_EQ(by_id[1]["result"], json::object());
  EXPECT_EQ(by_id[2]["result"]["structuredContent"]["altitude_m"], 12.5);
  EXPECT_EQ(by_id[3]["error"]["code"], -32601);
}

TEST_F(McpProtocolTest, ABatchOfNotificationsGetsNoAnswer) {
  initialize("2025-03-26");
  MessageSink sink;
  EXPECT_FALSE(protocol.handle(json::array({json{{"jsonrpc", "2.0"}, {"method", "notifications/initialized"}}}), std::ref(sink)));
  EXPECT_TRUE(sink.all().empty());
}

TEST_F(McpProtocolTest, BatchesAreRefusedIn20250618AndWhenEmpty) {
  initialize("2025-06-18");
  const json refused = ask(json::array({request(1, "ping")}));
  EXPECT_EQ(refused["error"]["code"], -32600);
  EXPECT_NE(refused["error"]["message"].get<std::string>().find("2025-06-18"), std::string::npos);
  EXPECT_EQ(ask(json::array())["error"]["code"], -32600);
}

TEST_F(McpProtocolTest, WantsProgressSeesTheTokenInACallOrABatch) {
  EXPECT_TRUE(McpProtocol::wants_progress(call(1, "fly_to", json::object(), {{"progressToken", 1}})));
  EXPECT_FALSE(McpProtocol::wants_progress(call(1, "fly_to")));
  EXPECT_TRUE(McpProtocol::wants_progress(json::array({request(1, "ping"), call(2, "x", json::object(), {{"progressToken", 1}})})));
}

TEST_F(McpProtocolTest, AfterShutdownNothingIsAnswered) {
  initialize();
  protocol.shutdown();
  MessageSink sink;
  EXPECT_FALSE(protocol.handle(request(1, "ping"), std::ref(sink)));
  EXPECT_TRUE(sink.all().empty());
}

}  // namespace
}  // namespace a3::agent::mcp
