// The MCP Streamable HTTP transport against abusive clients (issue 14), through the same guard
// as serve-model (agent/http/guarded_server.hpp): slow clients trickling request heads while a
// session keeps being served, the connection limit's 503, 411 / 400 for bodies without or with a
// malformed Content-Length, all as JSON-RPC errors; and bodies that parse as JSON only loosely
// (duplicate keys, excessive depth) refused with the parse error -32700.
#include "agent/mcp/mcp_server.hpp"
#include "tests/mcp_protocol/fake_mcp_rig.hpp"
#include "tests/raw_http_client.hpp"

#include <gtest/gtest.h>
#include <httplib.h>

#include <algorithm>
#include <cstdio>
#include <thread>

namespace a3::agent::mcp {
namespace {

using nlohmann::json;
using testing::FakeMcpRig;
using namespace std::chrono_literals;
namespace raw = a3::raw_http;

const json kInitialize = json::parse(
    R"({"jsonrpc":"2.0","id":0,"method":"initialize","params":{"protocolVersion":"2025-06-18","capabilities":{},"clientInfo":{"name":"t","version":"1"}}})");

class McpHttpAbuseTest : public ::testing::Test {
 protected:
  void serve(const http::HttpLimits& limits) {
    options.log = [](const std::string&) {};
    options.http_limits = limits;
    server = std::make_unique<McpServer>(rig, options);
    port = server->start_http();
  }
  httplib::Result post(const json& body, const httplib::Headers& headers = {}) {
    httplib::Client client("127.0.0.1", port);
    client.set_connection_timeout(5, 0);
    client.set_read_timeout(5, 0);
    return client.Post("/mcp", headers, body.dump(), "application/json");
  }
  std::string open_session() {
    const auto opened = post(kInitialize);
    if (!opened || opened->status != 200) return "";
    return opened->get_header_value("Mcp-Session-Id");
  }
  static std::string error_message(const std::string& body) {
    const json j = json::parse(body, nullptr, false);
    if (!j.is_object() || !j.contains("error")) return "(no JSON-RPC error: " + body + ")";
    return j["error"]["message"].get<std::string>();
  }

  FakeMcpRig rig;
  McpServerOptions options;
  std::unique_ptr<McpServer> server;
  int port = 0;
};

TEST_F(McpHttpAbuseTest, ASessionIsServedWhile100SlowClientsTrickleHeadsThatEndIn408) {
  http::HttpLimits limits;
  limits.header_timeout_s = 5.0;
  serve(limits);
  const std::string session = open_session();
  ASSERT_FALSE(session.empty());
  const auto slow_started = raw::RawClock::now();
  raw::SlowClients slow(port, 100, 3000ms, "POST /mcp HTTP/1.1\r\n");
  double slowest_s = 0.0;
  for (int i = 1; i <= 10; ++i) {
    const auto t0 = raw::RawClock::now();
    const auto r = post(json{{"jsonrpc", "2.0"}, {"id", i}, {"method", "ping"}},
                        {{"Mcp-Session-Id", session}, {"MCP-Protocol-Version", "2025-06-18"}});
    slowest_s = std::max(slowest_s, std::chrono::duration<double>(raw::RawClock::now() - t0).count());
    ASSERT_TRUE(r) << "ping " << i << " failed: " << httplib::to_string(r.error());
    EXPECT_EQ(r->status, 200) << r->body;
    std::this_thread::sleep_for(200ms);
  }
  std::printf("with 100 slow clients: 10 pings, slowest %.1f ms\n", 1e3 * slowest_s);
  EXPECT_LT(slowest_s, 2.0);
  EXPECT_EQ(slow.still_open(), 100);
  while (slow.still_open() > 0 && raw::RawClock::now() - slow_started < 9s) std::this_thread::sleep_for(50ms);
  EXPECT_EQ(slow.still_open(), 0) << "slow clients outlived the 5 s head deadline";
  for (const int status : slow.statuses()) EXPECT_EQ(status, 408);
  const json refusal = json::parse(raw::RawResponse{408, slow.first_received()}.body(), nullptr, false);
  EXPECT_EQ(refusal["error"]["code"], -32600) << slow.first_received();
  EXPECT_EQ(refusal["error"]["message"], "request head not received within 5 s");
}

TEST_F(McpHttpAbuseTest, AConnectionBeyondTheLimitIs503AsAJsonRpcError) {
  http::HttpLimits limits;
  limits.max_connections = 2;
  serve(limits);
  raw::SlowClients holders(port, 2, 3000ms, "POST /mcp HTTP/1.1\r\n");
  std::this_thread::sleep_for(200ms);
  const auto refused = post(kInitialize);
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 503);
  EXPECT_EQ(refused->get_header_value("Retry-After"), "1");
  EXPECT_EQ(error_message(refused->body), "server busy: more than 2 connections open (--max-connections)");
}

TEST_F(McpHttpAbuseTest, APostWithoutOrWithAMalformedContentLengthIsRefused) {
  serve({});
  const std::string body = kInitialize.dump();
  const std::string head = "POST /mcp HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n";
  const raw::RawResponse missing = raw::exchange(port, head + "\r\n" + body);
  EXPECT_EQ(missing.status, 411) << missing.text;
  EXPECT_EQ(error_message(missing.body()), "Content-Length required: POST /mcp must send its body with a Content-Length header");
  const raw::RawResponse negative = raw::exchange(port, head + "Content-Length: -5\r\n\r\n" + body);
  EXPECT_EQ(negative.status, 400) << negative.text;
  EXPECT_EQ(error_message(negative.body()), "malformed Content-Length '-5': must be a decimal byte count");
}

TEST_F(McpHttpAbuseTest, DuplicateKeysAndDeepNestingAreParseErrors) {
  serve({});
  httplib::Client client("127.0.0.1", port);
  const auto duplicate = client.Post("/mcp", R"({"jsonrpc":"2.0","id":1,"id":2,"method":"initialize"})", "application/json");
  ASSERT_TRUE(duplicate);
  EXPECT_EQ(duplicate->status, 400);
  EXPECT_EQ(json::parse(duplicate->body)["error"]["code"], -32700);
  EXPECT_NE(error_message(duplicate->body).find("duplicate"), std::string::npos) << duplicate->body;
  const auto deep = client.Post("/mcp", std::string(1000, '[') + std::string(1000, ']'), "application/json");
  ASSERT_TRUE(deep);
  EXPECT_EQ(deep->status, 400);
  EXPECT_EQ(json::parse(deep->body)["error"]["code"], -32700);
}

}  // namespace
}  // namespace a3::agent::mcp
