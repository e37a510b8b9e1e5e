// ModelServer against abusive clients (issue 14): slow clients that trickle a request head
// (slowloris) while legitimate requests keep being answered, the connection limit's 503, head
// and body deadlines (408), Content-Length refusals (411 / 400 / 413), and a bearer key followed
// by a NUL byte. Raw sockets where a client library would not send such bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include "agent/model_server/model_server.hpp"
#include "agent/model_server/reply_file_responder.hpp"
#include "tests/raw_http_client.hpp"

// After the project headers: httplib pulls in <resolv.h>, whose _res macro breaks Eigen.
#include <httplib.h>

namespace {

namespace ms = a3::agent::model_server;
namespace raw = a3::raw_http;
using nlohmann::json;
using namespace std::chrono_literals;

const std::string kGoodRequest = R"({"model":"m","messages":[{"role":"user","content":"hello there"}]})";

struct Served {
  explicit Served(ms::ModelServerOptions o) {
    o.host = "127.0.0.1";
    o.port = 0;
    o.quiet = true;
    server = std::make_unique<ms::ModelServer>(
        std::make_unique<ms::ReplyFileResponder>(std::vector<std::string>{R"({"intent":"hold"})"}), o);
    server->start();
  }
  httplib::Result post() const {
    httplib::Client c("127.0.0.1", server->port());
    c.set_connection_timeout(5, 0);
    c.set_read_timeout(5, 0);
    return c.Post("/v1/chat/completions", kGoodRequest, "application/json");
  }
  std::unique_ptr<ms::ModelServer> server;
};

std::string chat_post(const std::string& extra_headers, const std::string& body) {
  return "POST /v1/chat/completions HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n" + extra_headers +
         "\r\n" + body;
}

std::string error_message(const std::string& body) {
  const json j = json::parse(body, nullptr, false);
  if (!j.is_object() || !j.contains("error") || !j["error"].contains("message")) return "(no OpenAI error: " + body + ")";
  return j["error"]["message"].get<std::string>();
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
}

TEST(ModelServerAbuse, LegitimateRequestsAreServedWhile100SlowClientsTrickleHeadsThatEndIn408) {
  ms::ModelServerOptions o;
  o.http_limits.header_timeout_s = 6.0;
  Served s(o);
  const auto slow_started = raw::RawClock::now();
  raw::SlowClients slow(s.server->port(), 100, 3000ms, "POST /v1/chat/completions HTTP/1.1\r\n");
  std::vector<double> latencies_s;
  for (int i = 0; i < 20; ++i) {
    const auto t0 = raw::RawClock::now();
    const auto r = s.post();
    latencies_s.push_back(std::chrono::duration<double>(raw::RawClock::now() - t0).count());
    ASSERT_TRUE(r) << "request " << i << " failed: " << httplib::to_string(r.error());
    EXPECT_EQ(r->status, 200) << r->body;
    std::this_thread::sleep_for(200ms);
  }
  EXPECT_EQ(slow.still_open(), 100) << "the slow clients were cut before their head deadline";
  std::printf("with 100 slow clients: 20 requests, latency p50 %.1f ms, max %.1f ms\n", 1e3 * percentile(latencies_s, 0.5),
              1e3 * percentile(latencies_s, 1.0));
  EXPECT_LT(percentile(latencies_s, 1.0), 2.0);
  while (slow.still_open() > 0 && raw::RawClock::now() - slow_started < 10s) std::this_thread::sleep_for(50ms);
  EXPECT_EQ(slow.still_open(), 0) << "slow clients outlived the 6 s head deadline";
  for (const int status : slow.statuses()) EXPECT_EQ(status, 408);
  EXPECT_NE(error_message(raw::RawResponse{408, slow.first_received()}.body()).find("request head not received within 6 s"),
            std::string::npos)
      << slow.first_received();
  EXPECT_GE(slow.latest_close_s(), 5.5);
}

TEST(ModelServerAbuse, AConnectionBeyondTheLimitIs503InTheOpenAiShapeWithRetryAfter) {
  ms::ModelServerOptions o;
  o.http_limits.max_connections = 3;
  Served s(o);
  {
    raw::SlowClients holders(s.server->port(), 3, 3000ms, "GET /v1/models HTTP/1.1\r\n");
    std::this_thread::sleep_for(200ms);  // the three are accepted and counted
    const auto refused = s.post();
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 503);
    EXPECT_EQ(refused->get_header_value("Retry-After"), "1");
    EXPECT_EQ(error_message(refused->body), "server busy: more than 3 connections open (--max-connections)");
    const json error = json::parse(refused->body)["error"];
    EXPECT_EQ(error["type"], "server_error");
    EXPECT_EQ(error["code"], "server_busy");
    EXPECT_EQ(s.server->stats().refused_busy, 1u);
  }
  const auto deadline = raw::RawClock::now() + 3s;
  httplib::Result later = s.post();
  while ((!later || later->status != 200) && raw::RawClock::now() < deadline) {
    std::this_thread::sleep_for(50ms);
    later = s.post();
  }
  ASSERT_TRUE(later);
  EXPECT_EQ(later->status, 200) << "a freed connection slot was not reused";
}

TEST(ModelServerAbuse, ABodyThatComesTooSlowlyIs408) {
  ms::ModelServerOptions o;
  o.http_limits.body_timeout_s = 1.0;
  Served s(o);
  const int fd = raw::connect_loopback(s.server->port());
  raw::send_text(fd, chat_post("Content-Length: 100\r\n", R"({"model":)"));
  const auto t0 = raw::RawClock::now();
  const raw::RawResponse r = raw::read_until_close(fd, 5.0);
  ::close(fd);
  EXPECT_EQ(r.status, 408) << r.text;
  EXPECT_EQ(error_message(r.body()), "request body not received within 1 s");
  EXPECT_LT(std::chrono::duration<double>(raw::RawClock::now() - t0).count(), 3.0);
}

TEST(ModelServerAbuse, APostWithoutContentLengthIs411) {
  Served s({});
  const raw::RawResponse r = raw::exchange(s.server->port(), chat_post("", kGoodRequest));
  EXPECT_EQ(r.status, 411) << r.text;
  EXPECT_EQ(error_message(r.body()),
            "Content-Length required: POST /v1/chat/completions must send its body with a Content-Length header");
  EXPECT_EQ(json::parse(r.body())["error"]["code"], "length_required");
  const raw::RawResponse chunked = raw::exchange(s.server->port(), chat_post("Transfer-Encoding: chunked\r\n", "5\r\nhello\r\n0\r\n\r\n"));
  EXPECT_EQ(chunked.status, 411) << chunked.text;
}

TEST(ModelServerAbuse, AMalformedContentLengthIs400AndAnOversizeOne413) {
  Served s({});
  const raw::RawResponse negative = raw::exchange(s.server->port(), chat_post("Content-Length: -5\r\n", kGoodRequest));
  EXPECT_EQ(negative.status, 400) << negative.text;
  EXPECT_EQ(error_message(negative.body()), "malformed Content-Length '-5': must be a decimal byte count");
  const raw::RawResponse two = raw::exchange(
      s.server->port(), chat_post("Content-Length: 5\r\nContent-Length: 6\r\n", kGoodRequest));
  EXPECT_EQ(two.status, 400) << two.text;
  const raw::RawResponse huge = raw::exchange(s.server->port(), chat_post("Content-Length: 40000000\r\n", "{"));
  EXPECT_EQ(huge.status, 413) << huge.text;
  EXPECT_EQ(error_message(huge.body()), "request body larger than 33554432 bytes (Content-Length 40000000)");
  EXPECT_EQ(s.server->stats().bad_requests, 3u);
}

TEST(ModelServerAbuse, ABearerKeyFollowedByANulByteIsRefused) {
  const std::string key = "abuse-test-key-0c4f";
  ::setenv("A3_TEST_ABUSE_KEY", key.c_str(), 1);
  ms::ModelServerOptions o;
  o.require_key_env = "A3_TEST_ABUSE_KEY";
  Served s(o);
  const auto with = [&](const std::string& authorization) {
    return raw::exchange(s.server->port(), chat_post("Authorization: " + authorization + "\r\nContent-Length: " +
                                                         std::to_string(kGoodRequest.size()) + "\r\nConnection: close\r\n",
                                                     kGoodRequest))
        .status;
  };
  EXPECT_EQ(with("Bearer " + key + std::string(1, '\0') + "junk"), 401);
  EXPECT_EQ(with("Bearer " + key + "junk"), 401);
  EXPECT_EQ(with("Bearer " + key.substr(0, key.size() - 1)), 401);
  EXPECT_EQ(with("Bearer " + key.substr(0, key.size() - 1) + "%66"), 401);  // 'f' percent-encoded
  EXPECT_EQ(with("Bearer  " + key), 401);
  EXPECT_EQ(with("Bearer " + key), 200);
  ::unsetenv("A3_TEST_ABUSE_KEY");
}

TEST(ModelServerAbuse, LimitsOutOfRangeAreRefusedNamingTheFlag) {
  ms::ModelServerOptions o;
  o.http_limits.max_connections = 0;
  try {
    ms::ModelServer server(std::make_unique<ms::ReplyFileResponder>(std::vector<std::string>{"x"}), o);
    FAIL() << "max_connections 0 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--max-connections 0"), std::string::npos) << e.what();
  }
  o.http_limits.max_connections = 1;
  o.http_limits.header_timeout_s = 0.0;
  EXPECT_THROW(ms::ModelServer(std::make_unique<ms::ReplyFileResponder>(std::vector<std::string>{"x"}), o),
               std::invalid_argument);
}

}  // namespace
