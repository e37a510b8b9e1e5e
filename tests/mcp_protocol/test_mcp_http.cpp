// MCP's Streamable HTTP transport through a cpp-httplib client: the session header's rules,
// 202 for notifications, SSE for progress, DELETE, GET, Host, Origin and protocol-version checks.
#include "agent/mcp/mcp_server.hpp"
#include "tests/mcp_protocol/fake_mcp_rig.hpp"

#include <gtest/gtest.h>
#include <httplib.h>

#include <future>

namespace a3::agent::mcp {
namespace {

using nlohmann::json;
using testing::FakeMcpRig;

const json kInitialize = json::parse(
    R"({"jsonrpc":"2.0","id":0,"method":"initialize","params":{"protocolVersion":"2025-06-18","capabilities":{},"clientInfo":{"name":"t","version":"1"}}})");

json ping(int id) { return json{{"jsonrpc", "2.0"}, {"id", id}, {"method", "ping"}}; }

class McpHttpTest : public ::testing::Test {
 protected:
  McpHttpTest() {
    options.log = [](const std::string&) {};
    server = std::make_unique<McpServer>(rig, options);
    port = server->start_http();
    client = std::make_unique<httplib::Client>("127.0.0.1", port);
    client->set_read_timeout(10, 0);
  }
  httplib::Result post(const json& body, httplib::Headers headers) {
    headers.emplace("Accept", "application/json, text/event-stream");
    return client->Post("/mcp", headers, body.dump(), "application/json");
  }
  httplib::Headers session() { return {{"Mcp-Session-Id", session_id}, {"MCP-Protocol-Version", "2025-06-18"}}; }
  void open() {
    auto result = post(kInitialize, {});
    ASSERT_TRUE(result);
    ASSERT_EQ(result->status, 200);
    session_id = result->get_header_value("Mcp-Session-Id");
    ASSERT_EQ(session_id.size(), 32u);
  }

  FakeMcpRig rig;
  McpServerOptions options;
  std::unique_ptr<McpServer> server;
  int port = 0;
  std::unique_ptr<httplib::Client> client;
  std::string session_id;
};

TEST_F(McpHttpTest, InitializeIssuesASessionIdAndAnswersAsJson) {
  auto result = post(kInitialize, {});
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 200);
  EXPECT_NE(result->get_header_value("Content-Type").find("application/json"), std::string::npos);
  EXPECT_FALSE(result->get_header_value("Mcp-Session-Id").empty());
  EXPECT_EQ(json::parse(result->body)["result"]["protocolVersion"], "2025-06-18");
}

TEST_F(McpHttpTest, RequestsAfterInitializeNeedTheSessionId) {
  open();
  auto without = post(ping(1), {});
  ASSERT_TRUE(without);
  EXPECT_EQ(without->status, 400);
  EXPECT_NE(json::parse(without->body)["error"]["message"].get<std::string>().find("Mcp-Session-Id"), std::string::npos);
  auto unknown = post(ping(1), {{"Mcp-Session-Id", "0123"}});
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 404);
  auto good = post(ping(1), session());
  ASSERT_TRUE(good);
  EXPECT_EQ(good->status, 200);
  EXPECT_EQ(json::parse(good->body)["id"], 1);
}

TEST_F(McpHttpTest, ASecondInitializeIsAConflict) {
  open();
  auto again = post(kInitialize, {});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 409);
}

TEST_F(McpHttpTest, NotificationsAreAcceptedWith202AndNoBody) {
  open();
  auto result = post(json{{"jsonrpc", "2.0"}, {"method", "notifications/initialized"}}, session());
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 202);
  EXPECT_TRUE(result->body.empty());
}

TEST_F(McpHttpTest, AnUnsupportedProtocolVersionHeaderIs400) {
  open();
  auto result = post(ping(1), {{"Mcp-Session-Id", session_id}, {"MCP-Protocol-Version", "1999-01-01"}});
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 400);
  EXPECT_NE(result->body.find("1999-01-01"), std::string::npos);
}

TEST_F(McpHttpTest, AForeignOriginIs403AndTheServersOwnIsServed) {
  auto foreign = post(kInitialize, {{"Origin", "https://evil.example"}});
  ASSERT_TRUE(foreign);
  EXPECT_EQ(foreign->status, 403);
  EXPECT_NE(json::parse(foreign->body)["error"]["message"].get<std::string>().find("--allow-origin"), std::string::npos);
  auto foreign_form = client->Post("/mcp", {{"Origin", "http://evil.example"}}, "a=1", "application/x-www-form-urlencoded");
  ASSERT_TRUE(foreign_form);
  EXPECT_EQ(foreign_form->status, 403);  // the origin is judged before anything else
  auto other_local_page = post(kInitialize, {{"Origin", "http://localhost:6274"}});
  ASSERT_TRUE(other_local_page);
  EXPECT_EQ(other_local_page->status, 403);  // another port is another origin: allowed only with --allow-origin
  auto null_origin = post(kInitialize, {{"Origin", "null"}});
  ASSERT_TRUE(null_origin);
  EXPECT_EQ(null_origin->status, 403);
  auto own = post(kInitialize, {{"Origin", "http://localhost:" + std::to_string(port)}});
  ASSERT_TRUE(own);
  EXPECT_EQ(own->status, 200);
  EXPECT_FALSE(own->has_header("Access-Control-Allow-Origin"));
}

TEST_F(McpHttpTest, AHostThatIsNotThisServerIs403DnsRebinding) {
  auto rebound = post(kInitialize, {{"Host", "evil.example:" + std::to_string(port)}});
  ASSERT_TRUE(rebound);
  EXPECT_EQ(rebound->status, 403);
  EXPECT_NE(json::parse(rebound->body)["error"]["message"].get<std::string>().find("evil.example"), std::string::npos);
  auto wrong_port = post(kInitialize, {{"Host", "127.0.0.1:1"}});
  ASSERT_TRUE(wrong_port);
  EXPECT_EQ(wrong_port->status, 403);
  auto by_name = post(kInitialize, {{"Host", "localhost:" + std::to_string(port)}});
  ASSERT_TRUE(by_name);
  EXPECT_EQ(by_name->status, 200);
}

TEST_F(McpHttpTest, BadBodiesAreRefusedClearly) {
  auto not_json = client->Post("/mcp", "{oops", "application/json");
  ASSERT_TRUE(not_json);
  EXPECT_EQ(not_json->status, 400);
  EXPECT_EQ(json::parse(not_json->body)["error"]["code"], -32700);
  auto form = client->Post("/mcp", "a=1", "application/x-www-form-urlencoded");
  ASSERT_TRUE(form);
  EXPECT_EQ(form->status, 415);
}

TEST_F(McpHttpTest, A20250326SessionWithoutTheVersionHeaderAcceptsABatch) {
  json initialize = kInitialize;
  initialize["params"]["protocolVersion"] = "2025-03-26";
  auto opened = post(initialize, {});
  ASSERT_TRUE(opened);
  session_id = opened->get_header_value("Mcp-Session-Id");
  const json batch = json::array({ping(1), json::parse(R"({"jsonrpc":"2.0","id":2,"method":"tools/call","params":{"name":"read_telemetry"}})")});
  auto result = post(batch, {{"Mcp-Session-Id", session_id}});
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 200);
  const json replies = json::parse(result->body);
  ASSERT_TRUE(replies.is_array()) << result->body;
  EXPECT_EQ(replies.size(), 2u);
}

TEST_F(McpHttpTest, AnAcceptThatAllowsNeitherJsonNorEventsIs406) {
  open();
  auto result = client->Post("/mcp", {{"Mcp-Session-Id", session_id}, {"Accept", "text/html"}}, ping(1).dump(), "application/json");
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 406);
}

TEST_F(McpHttpTest, ABodyOver8MiBIs413) {
  open();
  const std::string huge = R"({"jsonrpc":"2.0","id":1,"method":"ping","params":{"pad":")" + std::string(9u << 20, 'x') + "\"}}";
  auto result = client->Post("/mcp", session(), huge, "application/json");
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 413);
}

class McpHttpAllowedOriginTest : public McpHttpTest {
 protected:
  McpHttpAllowedOriginTest() {
    server.reset();
    options.http_origins.allowed_origins = {"http://localhost:6274"};
    options.http_origins.allowed_hosts = {"rig.example"};
    server = std::make_unique<McpServer>(rig, options);
    port = server->start_http();
    client = std::make_unique<httplib::Client>("127.0.0.1", port);
    client->set_read_timeout(10, 0);
  }
};

TEST_F(McpHttpAllowedOriginTest, AnAllowedPageGetsCorsAndItsPreflightIsAnswered) {
  auto preflight = client->Options("/mcp", {{"Origin", "http://localhost:6274"}, {"Access-Control-Request-Method", "POST"}});
  ASSERT_TRUE(preflight);
  EXPECT_EQ(preflight->status, 204);
  EXPECT_NE(preflight->get_header_value("Access-Control-Allow-Headers").find("Mcp-Session-Id"), std::string::npos);
  EXPECT_EQ(preflight->get_header_value("Access-Control-Allow-Origin"), "http://localhost:6274");
  auto opened = post(kInitialize, {{"Origin", "http://localhost:6274"}});
  ASSERT_TRUE(opened);
  EXPECT_EQ(opened->status, 200);
  EXPECT_EQ(opened->get_header_value("Access-Control-Expose-Headers"), "Mcp-Session-Id");
  auto foreign = client->Options("/mcp", {{"Origin", "https://evil.example"}, {"Access-Control-Request-Method", "POST"}});
  ASSERT_TRUE(foreign);
  EXPECT_EQ(foreign->status, 403);
  EXPECT_FALSE(foreign->has_header("Access-Control-Allow-Origin"));
}

TEST_F(McpHttpAllowedOriginTest, AHostNameGivenWithAllowHostIsAnswered) {
  auto named = post(kInitialize, {{"Host", "rig.example:" + std::to_string(port)}});
  ASSERT_TRUE(named);
  EXPECT_EQ(named->status, 200);
}

TEST_F(McpHttpTest, GetIs405) {
  open();
  auto result = client->Get("/mcp", session());
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 405);
}

TEST_F(McpHttpTest, ACallWithAProgressTokenStreamsProgressThenTheResponse) {
  open();
  rig.release();
  const json call = json::parse(
      R"({"jsonrpc":"2.0","id":3,"method":"tools/call","params":{"name":"fly_to","arguments":{},"_meta":{"progressToken":"p1"}}})");
  auto result = post(call, session());
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 200);
  EXPECT_NE(result->get_header_value("Content-Type").find("text/event-stream"), std::string::npos);
  std::vector<json> events;
  for (size_t at = result->body.find("data: "); at != std::string::npos; at = result->body.find("data: ", at + 1))
    events.push_back(json::parse(result->body.substr(at + 6, result->body.find('\n', at) - at - 6)));
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0]["method"], "notifications/progress");
  EXPECT_EQ(events[0]["params"]["progressToken"], "p1");
  EXPECT_EQ(events[1]["params"]["progress"], 1.0);
  EXPECT_EQ(events[2]["id"], 3);
  EXPECT_EQ(events[2]["result"]["structuredContent"]["arrived"], true);
}

TEST_F(McpHttpTest, APingIsAnsweredWhileACallBlocks) {
  open();
  auto flying = std::async(std::launch::async, [this] {
    httplib::Client other("127.0.0.1", port);
    other.set_read_timeout(10, 0);
    return other.Post("/mcp", session(), R"({"jsonrpc":"2.0","id":3,"method":"tools/call","params":{"name":"fly_to"}})",
                      "application/json");
  });
  ASSERT_TRUE(rig.wait_for_flying(std::chrono::seconds(10)));
  auto pong = post(ping(4), session());
  ASSERT_TRUE(pong);
  EXPECT_EQ(json::parse(pong->body)["id"], 4);
  rig.release();
  auto called = flying.get();
  ASSERT_TRUE(called);
  EXPECT_EQ(json::parse(called->body)["result"]["isError"], false);
}

TEST_F(McpHttpTest, DeleteEndsTheSessionAndWaitReturns) {
  open();
  auto waited = std::async(std::launch::async, [this] { server->wait_http(); });
  EXPECT_EQ(waited.wait_for(std::chrono::milliseconds(200)), std::future_status::timeout);
  auto deleted = client->Delete("/mcp", session());
  ASSERT_TRUE(deleted);
  EXPECT_EQ(deleted->status, 200);
  EXPECT_TRUE(rig.closed);
  ASSERT_EQ(waited.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  auto after = post(ping(1), session());
  ASSERT_TRUE(after);
  EXPECT_EQ(after->status, 404);
}

TEST_F(McpHttpTest, StopEndsWaitWithoutClosingTheSession) {
  open();
  auto waited = std::async(std::launch::async, [this] { server->wait_http(); });
  server->stop();
  server->stop();
  ASSERT_EQ(waited.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  EXPECT_FALSE(rig.closed);
}

TEST(McpHttpBind, StartAfterStopThrows) {
  FakeMcpRig rig;
  McpServerOptions options;
  options.log = [](const std::string&) {};
  McpServer server(rig, options);
  server.stop();
  EXPECT_THROW(server.start_http(), std::runtime_error);
}

TEST(McpHttpBind, ATakenPortThrowsNamingIt) {
  FakeMcpRig rig;
  McpServerOptions options;
  options.log = [](const std::string&) {};
  McpServer first(rig, options);
  options.http_port = first.start_http();
  McpServer second(rig, options);
  try {
    second.start_http();
    FAIL() << "binding a taken port should throw";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(std::to_string(options.http_port)), std::string::npos);
  }
}

}  // namespace
}  // namespace a3::agent::mcp
