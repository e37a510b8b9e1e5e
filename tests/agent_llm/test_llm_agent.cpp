// The llm agent's attempt ladder against a fake OpenAI-compatible server on 127.0.0.1: an invalid
// reply is retried with the problems and the format restated, then with strict rules; three
// failures give an error decision without actions; attempts, usage and latency are recorded
// and the API key reaches only the Authorization header.
#include <gtest/gtest.h>

#include "agent/llm/llm_agent.hpp"
#include "tests/agent_llm/llm_test_support.hpp"

namespace a3 {
namespace {

using namespace agent::llm;

const char* kKey = "sk-test-9f2c1e77d0";
const char* kValid =
    R"({"intent": "preflight_check", "text": "Checking the vehicle.", "actions": [{"type": "mcp", "name": "read_telemetry", "args": {}}, {"type": "a2a", "to": "weather_service", "task": "request_weather_update", "payload": {}}]})";

std::unique_ptr<LlmAgent> agent_for(const test::FakeChatServer& server) {
  LlmEndpoint e;
  e.base_url = server.base_url();
  e.model = "fake-model";
  e.api_key = kKey;
  e.max_retries = 0;
  e.total_timeout_s = 20.0;
  return std::make_unique<LlmAgent>(std::make_unique<LlmClient>(e));
}

// The messages of a recorded request.
std::vector<std::pair<std::string, std::string>> messages_of(const nlohmann::json& request) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& m : request["messages"]) out.emplace_back(m.value("role", ""), m.value("content", ""));
  return out;
}

struct Fixture : ::testing::Test {
  test::PlayedContext played = test::play_scripted("survey-field", 0);
  agent::AgentContext context = played.context(1, test::normal_net());
  test::FakeChatServer server;
};

TEST_F(Fixture, ValidFirstReplyIsOneAttempt) {
  server.reply(kValid, 1200, 60);
  const agent::AgentDecision d = agent_for(server)->decide(context);
  EXPECT_TRUE(d.error.empty()) << d.error;
  EXPECT_EQ(d.attempts, 1);
  EXPECT_EQ(d.intent, "preflight_check");
  EXPECT_EQ(d.text, "Checking the vehicle.");
  ASSERT_EQ(d.actions.size(), 2u);
  EXPECT_EQ(d.actions[1]["task"], "request_weather_update");
  EXPECT_EQ(d.usage.value("total_tokens", 0), 1260);
  EXPECT_EQ(d.usage.value("prompt_tokens", 0), 1200);
  ASSERT_EQ(d.attempt_log.size(), 1u);
  EXPECT_EQ(d.attempt_log[0]["outcome"], "ok");
  EXPECT_GT(d.latency_s, 0.0);
  EXPECT_GE(d.latency_s, d.attempt_log[0]["wall_time_s"].get<double>());

  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0]["model"], "fake-model");
  const auto m = messages_of(requests[0]);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].first, "system");
  EXPECT_EQ(m[1].first, "user");
  EXPECT_NE(m[1].second.find("\"a3_context\":1"), std::string::npos);
  // The key went in the Authorization header, and nowhere else.
  EXPECT_EQ(server.authorizations()[0], std::string("Bearer ") + kKey);
  EXPECT_EQ(requests[0].dump().find(kKey), std::string::npos);
}

TEST_F(Fixture, InvalidThenValidIsTwoAttemptsAndTheRetryRestatesTheFormatAndTheProblem) {
  server.reply(R"({"intent": "go", "text": "", "actions": [{"type": "mcp", "name": "fly_to", "args": {"x": 1}}]})", 1000, 40);
  server.reply(kValid, 1100, 50);
  const agent::AgentDecision d = agent_for(server)->decide(context);
  EXPECT_TRUE(d.error.empty()) << d.error;
  EXPECT_EQ(d.attempts, 2);
  EXPECT_EQ(d.intent, "preflight_check");
  EXPECT_EQ(d.actions.size(), 2u);
  EXPECT_EQ(d.usage.value("prompt_tokens", 0), 2100);
  EXPECT_EQ(d.usage.value("completion_tokens", 0), 90);
  EXPECT_EQ(d.usage.value("total_tokens", 0), 2190);
  ASSERT_EQ(d.attempt_log.size(), 2u);
  EXPECT_EQ(d.attempt_log[0]["outcome"], "invalid_reply");
  EXPECT_NE(d.attempt_log[0]["problems"][0].get<std::string>().find("actions/0/name: unknown tool 'fly_to'"),
            std::string::npos);
  EXPECT_NE(d.attempt_log[0]["reply"].get<std::string>().find("fly_to"), std::string::npos);
  EXPECT_EQ(d.attempt_log[1]["outcome"], "ok");
  const double walls = d.attempt_log[0]["wall_time_s"].get<double>() + d.attempt_log[1]["wall_time_s"].get<double>();
  EXPECT_GE(d.latency_s, walls);

  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 2u);
  const auto m = messages_of(requests[1]);
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[2].first, "assistant");
  EXPECT_NE(m[2].second.find("fly_to"), std::string::npos);
  EXPECT_EQ(m[3].first, "user");
  EXPECT_NE(m[3].second.find("actions/0/name: unknown tool 'fly_to'"), std::string::npos);
  EXPECT_NE(m[3].second.find(reply_format_text()), std::string::npos);
  EXPECT_EQ(m[0].second.find("STRICT RULES"), std::string::npos);
}

TEST_F(Fixture, ThreeInvalidRepliesGiveAnErrorDecisionWithoutActions) {
  server.reply("I would take off now.", 900, 10);
  server.reply(R"({"intent": "takeoff", "actions": [{"type": "mcp", "name": "takeoff", "args": {"altitude_m": 9000}}]})", 950, 20);
  server.reply(R"({"intent": "takeoff", "actions": [{"type": "a2a", "to": "tower", "task": "path_plan", "payload": {}}]})", 990, 20);
  server.reply(kValid);  // never asked for: three attempts at most
  agent::AgentDecision d;
  ASSERT_NO_THROW(d = agent_for(server)->decide(context));
  EXPECT_FALSE(d.error.empty());
  EXPECT_NE(d.error.find("no usable reply after 3 attempts"), std::string::npos) << d.error;
  EXPECT_NE(d.error.find("actions/0/to: task 'path_plan' goes to 'ground_station', not 'tower'"), std::string::npos) << d.error;
  EXPECT_TRUE(d.actions.is_array());
  EXPECT_TRUE(d.actions.empty());
  EXPECT_EQ(d.attempts, 3);
  EXPECT_EQ(d.usage.value("prompt_tokens", 0), 900 + 950 + 990);
  ASSERT_EQ(d.attempt_log.size(), 3u);
  EXPECT_NE(d.attempt_log[0]["problems"][0].get<std::string>().find("reply: no JSON object"), std::string::npos);
  EXPECT_NE(d.attempt_log[1]["problems"][0].get<std::string>().find("actions/0/args/altitude_m"), std::string::npos);
  for (const auto& a : d.attempt_log) EXPECT_EQ(a["outcome"], "invalid_reply");

  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 3u);
  const auto third = messages_of(requests[2]);
  EXPECT_NE(third[0].second.find("STRICT RULES"), std::string::npos);
  EXPECT_NE(third.back().second.find("Reply with only the JSON object"), std::string::npos);
  EXPECT_NE(third.back().second.find("actions/0/args/altitude_m"), std::string::npos);
}

TEST_F(Fixture, AFailedCallIsAFailedAttemptAndIsRetried) {
  server.fail(400, R"({"error": {"message": "context length exceeded", "type": "invalid_request_error"}})");
  server.reply(kValid, 500, 30);
  const agent::AgentDecision d = agent_for(server)->decide(context);
  EXPECT_TRUE(d.error.empty()) << d.error;
  EXPECT_EQ(d.attempts, 2);
  ASSERT_EQ(d.attempt_log.size(), 2u);
  EXPECT_EQ(d.attempt_log[0]["outcome"], "call_failed");
  EXPECT_EQ(d.attempt_log[0]["http_status"], 400);
  EXPECT_FALSE(d.attempt_log[0]["problems"][0].get<std::string>().empty());
  const auto m = messages_of(server.requests()[1]);
  ASSERT_EQ(m.size(), 3u) << "no reply to echo after a failed call";
  EXPECT_NE(m[2].second.find("did not arrive or could not be read"), std::string::npos);
  EXPECT_EQ(d.usage.value("total_tokens", 0), 530);
}

TEST_F(Fixture, AnUnreachableServerGivesAnErrorDecisionNotACrash) {
  LlmEndpoint e;
  e.base_url = "http://127.0.0.1:9/v1";  // discard port: nothing listens
  e.model = "m";
  e.api_key = kKey;
  e.max_retries = 0;
  e.connect_timeout_s = 2.0;
  e.total_timeout_s = 5.0;
  LlmAgent a(std::make_unique<LlmClient>(e));
  agent::AgentDecision d;
  ASSERT_NO_THROW(d = a.decide(context));
  // No HTTP answer: the correction ladder stops after the first attempt (a stricter prompt
  // cannot reach a server that does not answer).
  EXPECT_EQ(d.attempts, 1);
  EXPECT_FALSE(d.error.empty());
  EXPECT_TRUE(d.actions.empty());
  for (const auto& x : d.attempt_log) EXPECT_EQ(x["outcome"], "call_failed");
}

TEST_F(Fixture, TheKeyNeverReachesTheDecision) {
  // Even a server that echoes the request's Authorization header into its error.
  server.fail(401, std::string(R"({"error": {"message": "bad key Bearer )") + kKey + R"("}})");
  server.reply(std::string(R"({"intent": "x", "text": ")") + kKey + R"(", "actions": []})");
  server.reply(kValid);
  const agent::AgentDecision d = agent_for(server)->decide(context);
  // The client redacts the key from the response body before anything reads it, so the second
  // reply is used with the key replaced.
  EXPECT_EQ(d.attempts, 2);
  EXPECT_TRUE(d.error.empty()) << d.error;
  EXPECT_NE(d.text.find("[redacted]"), std::string::npos) << d.text;
  nlohmann::json all = {{"intent", d.intent}, {"text", d.text}, {"actions", d.actions}, {"usage", d.usage},
                        {"attempt_log", d.attempt_log}, {"error", d.error}};
  EXPECT_EQ(all.dump().find(kKey), std::string::npos) << all.dump(2);
}

TEST(LlmAgentChatFunction, ExceptionsFromTheCallAreFailedAttempts) {
  const auto played = test::play_scripted("survey-field", 0);
  int calls = 0;
  LlmAgent a(
      [&calls](const ChatRequest&) -> LlmCallResult {
        ++calls;
        throw std::runtime_error("boom");
      },
      "");
  const agent::AgentDecision d = a.decide(played.context(1, test::normal_net()));
  EXPECT_EQ(calls, 3);
  EXPECT_NE(d.error.find("boom"), std::string::npos);
  EXPECT_TRUE(d.actions.empty());
}

}  // namespace
}  // namespace a3
