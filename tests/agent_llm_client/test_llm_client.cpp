// LlmClient against a scripted OpenAI-compatible server: success, retries (429 with
// Retry-After, 5xx, network errors), timeouts, final errors, malformed responses, the
// response_format fallback, keep-alive, and that the API key never leaves the Authorization
// header.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "agent/llm/llm_client.hpp"
#include "tests/agent_llm_client/scripted_openai_server.hpp"

namespace {

using a3::agent::llm::ChatMessage;
using a3::agent::llm::LlmCallResult;
using a3::agent::llm::LlmClient;
using a3::agent::llm::LlmEndpoint;
using a3::test::completion_body;
using a3::test::ScriptedOpenAiServer;
using a3::test::ScriptedReply;
using nlohmann::json;

const std::string kKey = "sk-a3test-DISTINCTIVE-7Qx9Zk2Lw4";

LlmEndpoint endpoint_for(const std::string& base_url) {
  LlmEndpoint e;
  e.base_url = base_url;
  e.model = "test-model";
  e.connect_timeout_s = 2.0;
  e.total_timeout_s = 5.0;
  e.max_retries = 3;
  e.backoff_initial_s = 0.5;
  e.backoff_max_s = 10.0;
  return e;
}

const std::vector<ChatMessage> kMessages = {{"system", "Answer in JSON."}, {"user", "Where is the drone?"}};

// A client whose backoff sleeps are recorded instead of slept.
struct TestClient {
  explicit TestClient(LlmEndpoint e) : client(std::move(e)) {
    client.set_sleep_for_tests([this](double s) { sleeps.push_back(s); });
  }
  LlmCallResult chat() { return client.chat(kMessages); }
  LlmClient client;
  std::vector<double> sleeps;
};

ScriptedReply ok_reply(const std::string& content = R"({"intent":"hold"})") {
  return {200, completion_body(content, {{"prompt_tokens", 12}, {"completion_tokens", 5}, {"total_tokens", 17}})};
}

TEST(LlmClient, SuccessRecordsContentUsageCostAndSendsTheRequestAsOpenAiDefines) {
  const json usage = {{"prompt_tokens", 1275},
                      {"completion_tokens", 2888},
                      {"total_tokens", 4163},
                      {"cost", 0.049695},
                      {"is_byok", false},
                      {"prompt_tokens_details", {{"cached_tokens", 0}}}};
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence(
      {{200, completion_body(R"({"intent":"take off"})", usage, "openai/gpt-4.1-mini"), {}, 0.2}}));
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult r = c.chat();
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.content, R"({"intent":"take off"})");
  EXPECT_EQ(r.finish_reason, "stop");
  EXPECT_EQ(r.model, "openai/gpt-4.1-mini");
  EXPECT_EQ(r.usage.prompt_tokens, 1275);
  EXPECT_EQ(r.usage.completion_tokens, 2888);
  EXPECT_EQ(r.usage.total_tokens, 4163);
  ASSERT_TRUE(r.usage.cost_usd.has_value());
  EXPECT_DOUBLE_EQ(*r.usage.cost_usd, 0.049695);
  EXPECT_EQ(r.usage.raw, usage);
  EXPECT_EQ(r.http_status, 200);
  EXPECT_EQ(r.http_attempts, 1);
  EXPECT_TRUE(r.error.empty());
  EXPECT_GE(r.wall_time_s, 0.2);  // the server's delay is part of the call
  EXPECT_LT(r.wall_time_s, 4.0);
  EXPECT_TRUE(c.sleeps.empty());

  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 1u);
  const json& body = requests[0].body;
  EXPECT_EQ(body["model"], "test-model");
  EXPECT_EQ(body["temperature"], 0.0);
  EXPECT_EQ(body["max_tokens"], 4096);
  EXPECT_EQ(body["response_format"], json({{"type", "json_object"}}));
  ASSERT_EQ(body["messages"].size(), 2u);
  EXPECT_EQ(body["messages"][0], json({{"role", "system"}, {"content", "Answer in JSON."}}));
  EXPECT_EQ(body["messages"][1]["content"], "Where is the drone?");
  EXPECT_EQ(requests[0].authorization, "");  // no key, no header
}

TEST(LlmClient, NoResponseFormatWhenJsonOutputIsOff) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({ok_reply()}));
  LlmEndpoint e = endpoint_for(server.base_url());
  e.json_output = false;
  e.temperature = 0.7;
  e.max_tokens = 100;
  TestClient c(e);
  ASSERT_TRUE(c.chat().ok);
  const json body = server.requests().at(0).body;
  EXPECT_FALSE(body.contains("response_format"));
  EXPECT_EQ(body["temperature"], 0.7);
  EXPECT_EQ(body["max_tokens"], 100);
}

TEST(LlmClient, RetriesA429AfterTheServersRetryAfter) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence(
      {{429, R"({"error":{"message":"rate limited","type":"rate_limit_error"}})", {{"Retry-After", "2"}}},
       ok_reply()}));
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult r = c.chat();
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(c.sleeps.size(), 1u);
  EXPECT_DOUBLE_EQ(c.sleeps[0], 2.0);
  EXPECT_EQ(r.http_attempts, 2);
  ASSERT_EQ(r.attempts.size(), 2u);
  EXPECT_EQ(r.attempts[0].http_status, 429);
  EXPECT_NE(r.attempts[0].error.find("rate limited"), std::string::npos);
  EXPECT_DOUBLE_EQ(r.attempts[0].backoff_s, 2.0);
  EXPECT_EQ(r.attempts[1].http_status, 200);
  EXPECT_EQ(r.http_status, 200);
}

TEST(LlmClient, RetryAfterIsCappedByTheBackoffMaximum) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{429, "{}", {{"Retry-After", "600"}}}, ok_reply()}));
  LlmEndpoint e = endpoint_for(server.base_url());
  e.backoff_max_s = 3.0;
  TestClient c(e);
  ASSERT_TRUE(c.chat().ok);
  EXPECT_EQ(c.sleeps, std::vector<double>({3.0}));
}

TEST(LlmClient, Retries503WithExponentialBackoff) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{503, "busy"}, {503, "busy"}, ok_reply()}));
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult r = c.chat();
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(c.sleeps, std::vector<double>({0.5, 1.0}));
  EXPECT_EQ(r.http_attempts, 3);
  EXPECT_EQ(server.requests().size(), 3u);
}

TEST(LlmClient, Gives500UpAfterMaxRetriesNamingEveryAttempt) {
  ScriptedOpenAiServer server(
      ScriptedOpenAiServer::sequence({{500, R"({"error":{"message":"upstream exploded"}})"}}));
  LlmEndpoint e = endpoint_for(server.base_url());
  e.max_retries = 2;
  TestClient c(e);
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.http_attempts, 3);
  EXPECT_EQ(r.http_status, 500);
  EXPECT_EQ(server.requests().size(), 3u);
  EXPECT_EQ(c.sleeps, std::vector<double>({0.5, 1.0}));
  EXPECT_NE(r.error.find("failed after 3 attempts"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("HTTP 500: upstream exploded"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(server.base_url() + "/chat/completions"), std::string::npos) << r.error;
}

TEST(LlmClient, BackoffIsCappedAtItsMaximum) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{502, ""}}));
  LlmEndpoint e = endpoint_for(server.base_url());
  e.max_retries = 5;
  e.backoff_initial_s = 1.0;
  e.backoff_max_s = 5.0;
  TestClient c(e);
  EXPECT_FALSE(c.chat().ok);
  EXPECT_EQ(c.sleeps, std::vector<double>({1.0, 2.0, 4.0, 5.0, 5.0}));
}

TEST(LlmClient, NetworkErrorOnAClosedPortIsRetriedThenFails) {
  // A port that was just free: bind, read the port, close.
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  socklen_t len = sizeof addr;
  ASSERT_EQ(::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len), 0);
  ::close(fd);
  const int port = ntohs(addr.sin_port);

  LlmEndpoint e = endpoint_for("http://127.0.0.1:" + std::to_string(port) + "/v1");
  e.max_retries = 2;
  TestClient c(e);
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.http_attempts, 3);
  EXPECT_EQ(r.http_status, 0);
  EXPECT_EQ(c.sleeps.size(), 2u);
  EXPECT_NE(r.error.find("onnect"), std::string::npos) << r.error;  // "connection failed: Failed to connect ..."
}

TEST(LlmClient, ASlowServerTimesOut) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{200, completion_body("late"), {}, 1.5}}));
  LlmEndpoint e = endpoint_for(server.base_url());
  e.total_timeout_s = 0.3;
  e.max_retries = 1;
  TestClient c(e);
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.http_attempts, 2);  // a timeout is retried
  EXPECT_NE(r.error.find("timed out"), std::string::npos) << r.error;
  EXPECT_LT(r.wall_time_s, 1.4);  // gave up before the server answered
}

TEST(LlmClient, A400IsNotRetried) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence(
      {{400, R"({"error":{"message":"'messages' must be a non-empty array","type":"invalid_request_error"}})"}}));
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.http_attempts, 1);
  EXPECT_EQ(r.http_status, 400);
  EXPECT_TRUE(c.sleeps.empty());
  EXPECT_NE(r.error.find("HTTP 400: 'messages' must be a non-empty array"), std::string::npos) << r.error;
}

TEST(LlmClient, ABodyThatIsNotJsonIsAClearError) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{200, "<html>Bad gateway</html>"}}));
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.http_attempts, 1);
  EXPECT_NE(r.error.find("response from " + server.base_url() + "/chat/completions: not JSON"), std::string::npos)
      << r.error;
  EXPECT_NE(r.error.find("body starts: <html>Bad gateway</html>"), std::string::npos) << r.error;
}

TEST(LlmClient, NoChoicesIsAClearError) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{200, R"({"id":"x","choices":[]})"}}));
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("no choices[0]"), std::string::npos) << r.error;
}

TEST(LlmClient, NullContentWithoutToolCallsIsAClearError) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{200, completion_body(nullptr)}}));
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("no choices[0].message.content and no tool_calls (body starts: {"), std::string::npos)
      << r.error;
}

TEST(LlmClient, AnErrorObjectWithStatus200IsAnError) {
  ScriptedOpenAiServer server(
      ScriptedOpenAiServer::sequence({{200, R"({"error":{"message":"provider returned error","code":502}})"}}));
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("error object: provider returned error"), std::string::npos) << r.error;
}

TEST(LlmClient, ContentAsAnArrayOfTextPartsIsJoined) {
  const json parts = json::array({{{"type", "text"}, {"text", "{\"intent\":"}}, {{"type", "text"}, {"text", "\"land\"}"}}});
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{200, completion_body(parts)}}));
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult r = c.chat();
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.content, R"({"intent":"land"})");
  EXPECT_EQ(r.usage.total_tokens, 0);  // no usage sent: zeros, not made up
}

TEST(LlmClient, AnAnswerLargerThanTheLimitIsAnError) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{200, completion_body(std::string(8000, 'x'))}}));
  LlmEndpoint e = endpoint_for(server.base_url());
  e.max_response_bytes = 1024;
  TestClient c(e);
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.http_attempts, 1);
  EXPECT_NE(r.error.find("larger than 1024 bytes"), std::string::npos) << r.error;
}

TEST(LlmClient, ResponseFormatRejectedIsDroppedForTheClientsLife) {
  ScriptedOpenAiServer server([](const a3::test::RecordedRequest& req, int) {
    if (req.body.contains("response_format")) {
      return ScriptedReply{400, R"({"error":{"message":"Unrecognized request argument supplied: response_format"}})"};
    }
    return ok_reply();
  });
  TestClient c(endpoint_for(server.base_url()));
  const LlmCallResult first = c.chat();
  ASSERT_TRUE(first.ok) << first.error;
  EXPECT_EQ(first.http_attempts, 2);
  EXPECT_TRUE(c.client.response_format_dropped());
  EXPECT_TRUE(c.sleeps.empty());
  const LlmCallResult second = c.chat();
  ASSERT_TRUE(second.ok) << second.error;
  EXPECT_EQ(second.http_attempts, 1);
  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 3u);
  EXPECT_TRUE(requests[0].body.contains("response_format"));
  EXPECT_FALSE(requests[1].body.contains("response_format"));
  EXPECT_FALSE(requests[2].body.contains("response_format"));
}

TEST(LlmClient, AnOther400IsNotMistakenForAResponseFormatRejection) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{400, R"({"error":{"message":"model not found"}})"}}));
  TestClient c(endpoint_for(server.base_url()));
  EXPECT_FALSE(c.chat().ok);
  EXPECT_FALSE(c.client.response_format_dropped());
  EXPECT_EQ(server.requests().size(), 1u);
}

TEST(LlmClient, ReusesItsConnectionAcrossCalls) {
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({ok_reply()}));
  TestClient c(endpoint_for(server.base_url()));
  ASSERT_TRUE(c.chat().ok);
  ASSERT_TRUE(c.chat().ok);
  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_EQ(requests[0].remote_port, requests[1].remote_port);
}

TEST(LlmClient, TheKeyGoesOnlyInTheAuthorizationHeader) {
  // The server echoes the key everywhere it can: in errors, in content, in headers.
  ScriptedOpenAiServer server([](const a3::test::RecordedRequest& req, int index) {
    const std::string auth = req.authorization;
    const std::string echoed = auth.size() > 7 ? auth.substr(7) : "none";
    switch (index) {
      case 0:
        return ScriptedReply{503, R"({"error":{"message":"overloaded for key )" + echoed + R"("}})"};
      case 1:
        return ScriptedReply{401, "Incorrect API key provided: " + echoed + " " + std::string(300, '.')};
      default:
        return ScriptedReply{200, completion_body("your key is " + echoed, {{"total_tokens", 1}, {"key", echoed}})};
    }
  });
  LlmEndpoint e = endpoint_for(server.base_url());
  e.api_key = kKey;
  TestClient c(e);
  const LlmCallResult failed = c.chat();  // 503 (retried), then 401 (final)
  EXPECT_FALSE(failed.ok);
  EXPECT_EQ(failed.http_attempts, 2);
  EXPECT_EQ(failed.error.find(kKey), std::string::npos) << failed.error;
  EXPECT_NE(failed.error.find("[redacted]"), std::string::npos) << failed.error;
  for (const auto& a : failed.attempts) EXPECT_EQ(a.error.find(kKey), std::string::npos) << a.error;
  EXPECT_NE(failed.error.find("HTTP 401"), std::string::npos) << failed.error;

  const LlmCallResult answered = c.chat();
  ASSERT_TRUE(answered.ok) << answered.error;
  EXPECT_EQ(answered.content.find(kKey), std::string::npos);
  EXPECT_EQ(answered.usage.to_json().dump().find(kKey), std::string::npos);

  for (const auto& req : server.requests()) {
    EXPECT_EQ(req.authorization, "Bearer " + kKey);
    EXPECT_EQ(req.body.dump().find(kKey), std::string::npos);
  }
  EXPECT_EQ(c.client.endpoint().api_key, kKey);  // kept, only to send
}

TEST(LlmClient, KeyIsRedactedEvenWhereAnExcerptWouldCutIt) {
  // The key straddles the 200-character excerpt boundary of a non-JSON body.
  ScriptedOpenAiServer server([](const a3::test::RecordedRequest& req, int) {
    return ScriptedReply{200, std::string(190, '#') + req.authorization.substr(7) + std::string(50, '#')};
  });
  LlmEndpoint e = endpoint_for(server.base_url());
  e.api_key = kKey;
  TestClient c(e);
  const LlmCallResult r = c.chat();
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.find(kKey.substr(0, 10)), std::string::npos) << r.error;
}

TEST(LlmClient, RejectsUnusableEndpoints) {
  LlmEndpoint e = endpoint_for("ftp://example.com/v1");
  EXPECT_THROW(LlmClient{e}, std::invalid_argument);
  e = endpoint_for("http://127.0.0.1:1/v1");
  e.model = "";
  EXPECT_THROW(LlmClient{e}, std::invalid_argument);
  e = endpoint_for("http://127.0.0.1:1/v1");
  e.total_timeout_s = 0.0;
  EXPECT_THROW(LlmClient{e}, std::invalid_argument);
  e = endpoint_for("http://127.0.0.1:1/v1");
  e.api_key = "abc\r\nX-Injected: 1";
  try {
    LlmClient client(e);
    FAIL() << "a key with a line break was accepted";
  } catch (const std::invalid_argument& err) {
    EXPECT_EQ(std::string(err.what()).find("abc"), std::string::npos);
  }
  e = endpoint_for("https://openrouter.ai/api/v1/");
  LlmClient client(e);
  EXPECT_EQ(client.endpoint().base_url, "https://openrouter.ai/api/v1");
  EXPECT_EQ(client.endpoint().provider, "openrouter");
}

}  // namespace
