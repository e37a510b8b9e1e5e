// Streaming in LlmClient (stream: true, server-sent events) against a tiny local SSE server:
// content deltas cut in the middle of a JSON string across chunks, parallel tool-call deltas
// merged by index, the usage chunk, [DONE], the time to the first and the last token; a stream
// that ends before [DONE] or whose connection drops is an error, not a hang. And the SSE line
// parser and the chunk assembler on their own.
#include <gtest/gtest.h>

#include <chrono>

#include "agent/llm/llm_client.hpp"
#include "agent/llm/sse_stream.hpp"
#include "tests/agent_llm_client/scripted_openai_server.hpp"
#include "tests/agent_llm_client/sse_test_server.hpp"

namespace {

using namespace a3::agent::llm;
using a3::test::SseTestServer;
using nlohmann::json;

constexpr double kPause_s = 0.05;

LlmEndpoint streaming_endpoint(const std::string& base_url) {
  LlmEndpoint e;
  e.base_url = base_url;
  e.model = "stream-model";
  e.connect_timeout_s = 2.0;
  e.total_timeout_s = 10.0;
  e.max_retries = 0;
  e.json_output = false;
  e.stream = true;
  return e;
}

std::string event(const json& chunk) { return "data: " + chunk.dump() + "\n\n"; }

json content_chunk(const std::string& piece) {
  return {{"id", "c1"}, {"object", "chat.completion.chunk"}, {"model", "stream-model"},
          {"choices", {{{"index", 0}, {"delta", {{"content", piece}}}, {"finish_reason", nullptr}}}}};
}

const std::string kUsage = event({{"id", "c1"}, {"choices", json::array()},
                                  {"usage", {{"prompt_tokens", 11}, {"completion_tokens", 4}, {"total_tokens", 15}}}});
const std::string kDone = "data: [DONE]\n\n";

// One event whose JSON text is cut in the middle of the content string "Hello \"world\" ✓".
std::vector<std::string> content_split_mid_string() {
  const std::string whole = event(content_chunk("Hello \"world\" \xE2\x9C\x93"));
  const std::size_t in_string = whole.find("wor");
  const std::size_t in_utf8 = whole.find("\xE2\x9C") + 1;  // inside the 3-byte character
  return {whole.substr(0, in_string), whole.substr(in_string, in_utf8 - in_string), whole.substr(in_utf8)};
}

TEST(LlmClientStream, ContentCutMidStringAcrossChunksIsAssembledWithUsageAndTokenTimes) {
  std::vector<std::string> chunks = {event({{"choices", {{{"index", 0}, {"delta", {{"role", "assistant"}}}}}}})};
  for (auto& c : content_split_mid_string()) chunks.push_back(c);
  chunks.push_back("data: " + content_chunk(" done.").dump() + "\r\n\r\n");  // CRLF lines
  chunks.push_back(": keep-alive comment\n\n");
  chunks.push_back(event({{"choices", {{{"index", 0}, {"delta", json::object()}, {"finish_reason", "stop"}}}}}));
  chunks.push_back(kUsage);
  chunks.push_back(kDone);
  SseTestServer server(chunks, kPause_s);
  LlmClient client(streaming_endpoint(server.base_url()));
  const LlmCallResult r = client.chat({{"user", "hi"}});
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.streamed);
  EXPECT_EQ(r.content, "Hello \"world\" \xE2\x9C\x93 done.");
  EXPECT_EQ(r.finish_reason, "stop");
  EXPECT_EQ(r.model, "stream-model");
  EXPECT_EQ(r.usage.total_tokens, 15);
  EXPECT_EQ(r.usage.prompt_tokens, 11);
  ASSERT_TRUE(r.ttft_s.has_value());
  ASSERT_TRUE(r.ttlt_s.has_value());
  // The first token is in the 4th chunk (3 pauses in), the last in the 5th (4 pauses in).
  EXPECT_GE(*r.ttft_s, 3 * kPause_s * 0.9);
  EXPECT_GE(*r.ttlt_s - *r.ttft_s, kPause_s * 0.9);
  EXPECT_LE(*r.ttlt_s, r.wall_time_s);
  ASSERT_EQ(r.attempts.size(), 1u);
  EXPECT_EQ(r.attempts[0].ttft_s, r.ttft_s);
  EXPECT_EQ(r.attempts[0].ttlt_s, r.ttlt_s);
  const json body = server.bodies().at(0);
  EXPECT_EQ(body["stream"], true);
  EXPECT_EQ(body["stream_options"], json({{"include_usage", true}}));
}

json tool_delta(int index, const json& fields) {
  json call = fields;
  call["index"] = index;
  json delta = {{"tool_calls", json::array({call})}};
  return {{"choices", json::array({{{"index", 0}, {"delta", delta}}})}};
}

TEST(LlmClientStream, ParallelToolCallDeltasAreMergedByIndex) {
  const std::vector<std::string> chunks = {
      event(tool_delta(0, {{"id", "call_a"}, {"type", "function"}, {"function", {{"name", "read_telemetry"}, {"arguments", ""}}}})),
      event(tool_delta(1, {{"id", "call_b"}, {"type", "function"}, {"function", {{"name", "navigate_to"}, {"arguments", "{\"x\": 1"}}}})),
      event(tool_delta(0, {{"function", {{"arguments", "{}"}}}})),
      event(tool_delta(1, {{"function", {{"arguments", "2.5, \"y\": -3}"}}}})),
      event({{"choices", {{{"index", 0}, {"delta", json::object()}, {"finish_reason", "tool_calls"}}}}}),
      kUsage,
      kDone};
  SseTestServer server(chunks, 0.0);
  LlmClient client(streaming_endpoint(server.base_url()));
  const LlmCallResult r = client.chat({{"user", "fly"}});
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.content, "");
  EXPECT_EQ(r.finish_reason, "tool_calls");
  ASSERT_EQ(r.tool_calls.size(), 2u);
  EXPECT_EQ(r.tool_calls[0].id, "call_a");
  EXPECT_EQ(r.tool_calls[0].name, "read_telemetry");
  EXPECT_EQ(r.tool_calls[0].arguments, "{}");
  EXPECT_EQ(r.tool_calls[1].id, "call_b");
  EXPECT_EQ(r.tool_calls[1].name, "navigate_to");
  EXPECT_EQ(json::parse(r.tool_calls[1].arguments), json({{"x", 12.5}, {"y", -3}}));
}

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

TEST(LlmClientStream, AStreamThatEndsBeforeDoneIsAnErrorNotAHang) {
  SseTestServer server({event(content_chunk("Hel")), event(content_chunk("lo"))}, 0.0);
  LlmClient client(streaming_endpoint(server.base_url()));
  const auto t0 = std::chrono::steady_clock::now();
  const LlmCallResult r = client.chat({{"user", "hi"}});
  EXPECT_LT(seconds(t0), 5.0);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("the stream ended before data: [DONE] (cut off)"), std::string::npos) << r.error;
  EXPECT_TRUE(is_endpoint_failure(r)) << "a cut stream is the network's fault, like a dropped connection";
}

TEST(LlmClientStream, AConnectionDroppedMidStreamIsAnErrorNotAHang) {
  SseTestServer server({event(content_chunk("Hel"))}, 0.0, SseTestServer::End::kDropConnection);
  LlmClient client(streaming_endpoint(server.base_url()));
  const auto t0 = std::chrono::steady_clock::now();
  const LlmCallResult r = client.chat({{"user", "hi"}});
  EXPECT_LT(seconds(t0), 5.0);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.http_status, 0);
  EXPECT_FALSE(r.error.empty());
}

TEST(LlmClientStream, AnErrorChunkInTheStreamIsNamed) {
  SseTestServer server({event(content_chunk("Hel")), event({{"error", {{"message", "upstream overloaded"}}}}), kDone}, 0.0);
  LlmClient client(streaming_endpoint(server.base_url()));
  const LlmCallResult r = client.chat({{"user", "hi"}});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("error in the stream: upstream overloaded"), std::string::npos) << r.error;
}

TEST(LlmClientStream, AServerThatIgnoresStreamAndAnswersJsonIsReadAsUsual) {
  a3::test::ScriptedOpenAiServer server(a3::test::ScriptedOpenAiServer::sequence({{200, a3::test::completion_body("plain")}}));
  LlmClient client(streaming_endpoint(server.base_url()));
  const LlmCallResult r = client.chat({{"user", "hi"}});
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.content, "plain");
  EXPECT_FALSE(r.streamed);
  EXPECT_FALSE(r.ttft_s.has_value());
  EXPECT_EQ(server.requests().at(0).body["stream"], true);
}

TEST(SseLineParser, EveryWayOfCuttingTheBytesGivesTheSameEvents) {
  const std::string bytes = "data: {\"a\": \"x\\ny\"}\r\n\r\n: comment\nevent: message\ndata: line1\ndata: line2\n\ndata:[DONE]\r\r";
  const std::vector<std::string> expected = {"{\"a\": \"x\\ny\"}", "line1\nline2", "[DONE]"};
  for (std::size_t cut = 0; cut <= bytes.size(); ++cut) {
    SseLineParser parser;
    std::vector<std::string> events;
    auto on = [&](const std::string& d) { events.push_back(d); };
    parser.feed(std::string_view(bytes).substr(0, cut), on);
    parser.feed(std::string_view(bytes).substr(cut), on);
    EXPECT_EQ(events, expected) << "cut at " << cut;
  }
}

TEST(ChatStreamAssembler, ANotJsonChunkIsAProblemAndTokensAreFlagged) {
  ChatStreamAssembler a;
  bool token = true;
  EXPECT_EQ(a.add(R"({"choices":[{"index":0,"delta":{"role":"assistant"}}]})", token), "");
  EXPECT_FALSE(token) << "a role delta is no token";
  EXPECT_EQ(a.add(R"({"choices":[{"index":0,"delta":{"content":"a"}}]})", token), "");
  EXPECT_TRUE(token);
  EXPECT_NE(a.add("{not json", token).find("not a JSON object"), std::string::npos);
}

}  // namespace
