// The llm agent in native tool-calling mode, against a fake chat function: the request carries
// every registry function as `tools` with tool_choice "required" and no JSON reply format; the
// model's tool_calls (parallel ones included) are the turn's actions and report_turn its intent
// and text (without it: the first call's function name and the content); the next turn's
// request holds the earlier turns as history, the agent's calls with the ids the model gave and
// each observation as a tool message answering its id; a text-only reply, an unknown function or
// arguments against the schema are retried with a stricter correction and then fail the turn
// with a clear error; a call that fails at the endpoint is marked as such in the attempt log.
#include <gtest/gtest.h>

#include "agent/llm/llm_agent.hpp"
#include "tests/agent_llm/llm_test_support.hpp"

namespace a3 {
namespace {

using namespace agent::llm;
using nlohmann::json;

LlmCallResult tool_reply(std::vector<ToolCall> calls, std::string content = "") {
  LlmCallResult r;
  r.ok = true;
  r.http_status = 200;
  r.http_attempts = 1;
  r.tool_calls = std::move(calls);
  r.content = std::move(content);
  r.finish_reason = "tool_calls";
  r.usage.prompt_tokens = 900;
  r.usage.completion_tokens = 40;
  r.usage.total_tokens = 940;
  return r;
}

LlmCallResult text_reply(const std::string& content) {
  LlmCallResult r = tool_reply({}, content);
  r.finish_reason = "stop";
  return r;
}

const ToolCall kTelemetry{"call_tel", "read_telemetry", "{}"};
const ToolCall kWeather{"call_wx", "a2a_request_weather_update", "{}"};
const ToolCall kReport{"call_rep", "report_turn", R"({"intent":"preflight_check","text":"Checking the vehicle."})"};

// A fake model: answers from a list (the last repeats) and keeps every request.
struct FakeModel {
  std::vector<LlmCallResult> answers;
  std::vector<ChatRequest> requests;
  ChatFunction function() {
    return [this](const ChatRequest& r) {
      requests.push_back(r);
      return answers[std::min(requests.size(), answers.size()) - 1];
    };
  }
};

LlmAgentOptions native() {
  LlmAgentOptions o;
  o.mode = ToolMode::kNative;
  return o;
}

struct Native : ::testing::Test {
  test::PlayedContext played = test::play_scripted("survey-field", 0);
  FakeModel model;
};

TEST_F(Native, ParallelToolCallsAreTheActionsAndReportTurnGivesIntentAndText) {
  model.answers = {tool_reply({kTelemetry, kWeather, kReport})};
  LlmAgent agent(model.function(), "", agent::ToolCatalog::builtin(), native());
  const agent::AgentDecision d = agent.decide(played.context(1, test::normal_net()));
  ASSERT_TRUE(d.error.empty()) << d.error;
  EXPECT_EQ(d.intent, "preflight_check");
  EXPECT_EQ(d.text, "Checking the vehicle.");
  ASSERT_EQ(d.actions.size(), 2u);
  EXPECT_EQ(d.actions[0], json({{"type", "mcp"}, {"name", "read_telemetry"}, {"args", json::object()}}));
  EXPECT_EQ(d.actions[1]["type"], "a2a");
  EXPECT_EQ(d.actions[1]["task"], "request_weather_update");
  EXPECT_EQ(d.actions[1]["to"], "weather_service");
  EXPECT_EQ(d.attempts, 1);
  EXPECT_EQ(d.attempt_log[0]["outcome"], "ok");
  EXPECT_EQ(d.attempt_log[0]["tool_mode"], "native");
  EXPECT_EQ(d.usage.value("total_tokens", 0), 940);

  ASSERT_EQ(model.requests.size(), 1u);
  const ChatRequest& r = model.requests[0];
  EXPECT_EQ(r.tools, agent::ToolCatalog::builtin().openai_tools());
  EXPECT_EQ(r.tool_choice, "required");
  ASSERT_EQ(r.messages.size(), 2u) << "system and the turn's user message: no history before turn 1";
  EXPECT_EQ(r.messages[0].role, "system");
  EXPECT_EQ(r.messages[0].content.find("Reply format"), std::string::npos);
  EXPECT_NE(r.messages[0].content.find("report_turn"), std::string::npos);
  EXPECT_EQ(r.messages[0].content.find("listed below"), std::string::npos) << "nothing is listed in native mode";
  EXPECT_EQ(r.messages[1].role, "user");
  EXPECT_EQ(r.messages[1].content, turn_prompt(played.context(1, test::normal_net()), {}, ToolMode::kNative));
  EXPECT_TRUE(find_context_block(r.messages[1].content).has_value()) << "the context block stays in the message";
}

TEST_F(Native, WithoutReportTurnTheIntentIsTheFirstFunctionAndTheTextTheContent) {
  model.answers = {tool_reply({kTelemetry}, "Reading the telemetry first.")};
  LlmAgent agent(model.function(), "", agent::ToolCatalog::builtin(), native());
  const agent::AgentDecision d = agent.decide(played.context(1, test::normal_net()));
  ASSERT_TRUE(d.error.empty()) << d.error;
  EXPECT_EQ(d.intent, "read_telemetry");
  EXPECT_EQ(d.text, "Reading the telemetry first.");
  EXPECT_EQ(d.actions.size(), 1u);
}

TEST_F(Native, OnlyReportTurnIsATurnWithoutActions) {
  model.answers = {tool_reply({{"r", "report_turn", R"({"intent":"confirm_landing","text":"Landed."})"}})};
  LlmAgent agent(model.function(), "", agent::ToolCatalog::builtin(), native());
  const agent::AgentDecision d = agent.decide(played.context(1, test::normal_net()));
  ASSERT_TRUE(d.error.empty()) << d.error;
  EXPECT_EQ(d.intent, "confirm_landing");
  EXPECT_TRUE(d.actions.empty());
}

TEST_F(Native, TheNextTurnCarriesTheCallsWithTheModelsIdsAndTheirObservationsAsToolMessages) {
  model.answers = {tool_reply({kTelemetry, kWeather, kReport})};
  LlmAgent agent(model.function(), "", agent::ToolCatalog::builtin(), native());
  const agent::AgentDecision first = agent.decide(played.context(1, test::normal_net()));
  ASSERT_TRUE(first.error.empty()) << first.error;
  // The turn as the conversation records it, and the supervisor's answer.
  agent::Turn t1;
  t1.number = 1;
  t1.speaker = "agent";
  t1.intent = first.intent;
  t1.text = first.text;
  t1.actions = first.actions;
  t1.obs = json::array({test::synthetic_observation(first.actions[0], false),
                        test::synthetic_observation(first.actions[1], false)});
  agent::Turn t2;
  t2.number = 2;
  t2.speaker = "user";
  t2.intent = "acknowledge";
  t2.text = "Understood, take off.";
  played.dialogue = {t1, t2};
  const agent::AgentDecision second = agent.decide(played.context(3, test::normal_net()));
  ASSERT_TRUE(second.error.empty()) << second.error;

  const std::vector<ChatMessage>& m = model.requests.at(1).messages;
  ASSERT_EQ(m.size(), 7u);  // system, assistant, 3 tool results, supervisor, the turn
  EXPECT_EQ(m[1].role, "assistant");
  ASSERT_EQ(m[1].tool_calls.size(), 3u);
  EXPECT_EQ(m[1].tool_calls[0].id, "call_tel");
  EXPECT_EQ(m[1].tool_calls[1].id, "call_wx");
  EXPECT_EQ(m[1].tool_calls[1].name, "a2a_request_weather_update");
  EXPECT_EQ(m[1].tool_calls[2].id, "call_rep");
  EXPECT_EQ(m[2].role, "tool");
  EXPECT_EQ(m[2].tool_call_id, "call_tel");
  EXPECT_EQ(json::parse(m[2].content), t1.obs[0]);
  EXPECT_EQ(m[3].tool_call_id, "call_wx");
  EXPECT_EQ(json::parse(m[3].content), t1.obs[1]);
  EXPECT_EQ(m[4].tool_call_id, "call_rep");
  EXPECT_EQ(m[5].role, "user");
  EXPECT_NE(m[5].content.find("Understood, take off."), std::string::npos);
  EXPECT_EQ(m[6].role, "user");
  EXPECT_TRUE(find_context_block(m[6].content).has_value());
}

TEST_F(Native, TurnsTheAgentDidNotMakeGetMadeUpIdsThatTheirResultsAnswer) {
  played = test::play_scripted("survey-field", 2);  // turn 1 by the scripted agent
  model.answers = {tool_reply({kTelemetry, kReport})};
  LlmAgent agent(model.function(), "", agent::ToolCatalog::builtin(), native());
  ASSERT_TRUE(agent.decide(played.context(3, test::normal_net())).error.empty());
  const std::vector<ChatMessage>& m = model.requests.at(0).messages;
  ASSERT_GE(m.size(), 3u);
  const auto& actions = played.dialogue[0].actions;
  ASSERT_EQ(m[1].tool_calls.size(), actions.size() + 1);
  for (std::size_t i = 0; i < actions.size(); ++i) {
    EXPECT_EQ(m[1].tool_calls[i].id, "call_1_" + std::to_string(i));
    EXPECT_EQ(m[1].tool_calls[i].name, agent::ToolCatalog::function_name_of(actions[i]));
    EXPECT_EQ(m[2 + i].tool_call_id, m[1].tool_calls[i].id);
  }
}

TEST_F(Native, AFailedTurnIsAnAssistantMessageWithItsErrorAndNoCalls) {
  agent::Turn failed;
  failed.number = 1;
  failed.speaker = "agent";
  failed.intent = "agent_error";
  failed.text = "agent error: no usable reply after 3 attempts: HTTP 400: bad request";
  agent::Turn reply;
  reply.number = 2;
  reply.speaker = "user";
  reply.intent = "acknowledge";
  reply.text = "Please try again.";
  played.dialogue = {failed, reply};
  const std::vector<ChatMessage> m =
      history_messages(played.context(3, test::normal_net()), agent::ToolCatalog::builtin(), {});
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].role, "assistant");
  EXPECT_EQ(m[0].content, failed.text);
  EXPECT_TRUE(m[0].tool_calls.empty());
  EXPECT_EQ(m[1].role, "user");
  EXPECT_EQ(m[1].content, "Supervisor (turn 2, intent acknowledge): Please try again.");
}

TEST_F(Native, ALongHistoryKeepsTheNewestObservationsWholeAndCutsTheOldestToTheirStatus) {
  played = test::play_scripted("survey-field", 10);
  DialogueLimits tight;
  tight.max_dialogue_chars = 1;  // everything but the newest keep_full_turns is cut
  tight.keep_full_turns = 2;
  const agent::AgentContext c = played.context(11, test::normal_net());
  const std::vector<ChatMessage> full = history_messages(c, agent::ToolCatalog::builtin(), {});
  const std::vector<ChatMessage> cut = history_messages(c, agent::ToolCatalog::builtin(), {}, tight);
  ASSERT_EQ(full.size(), cut.size()) << "the same turns and calls, only observations shortened";
  std::size_t full_chars = 0, cut_chars = 0;
  for (const auto& m : full) full_chars += m.content.size();
  for (const auto& m : cut) cut_chars += m.content.size();
  EXPECT_LT(cut_chars, full_chars);
  EXPECT_EQ(full.back().content, cut.back().content) << "the newest turn is whole";
}

TEST_F(Native, ATextOnlyReplyIsRetriedStricterThenFailsTheTurnWithAClearError) {
  model.answers = {text_reply("I will take off now.")};
  LlmAgent agent(model.function(), "", agent::ToolCatalog::builtin(), native());
  const agent::AgentDecision d = agent.decide(played.context(1, test::normal_net()));
  EXPECT_EQ(d.attempts, 3);
  EXPECT_TRUE(d.actions.empty());
  EXPECT_NE(d.error.find("no usable reply after 3 attempts"), std::string::npos) << d.error;
  EXPECT_NE(d.error.find("the reply called no function (it answered with text only: \"I will take off now.\")"),
            std::string::npos)
      << d.error;
  for (const auto& e : d.attempt_log) EXPECT_EQ(e["outcome"], "invalid_reply");
  ASSERT_EQ(model.requests.size(), 3u);
  const auto& second = model.requests[1].messages;
  EXPECT_EQ(second.back().role, "user");
  EXPECT_NE(second.back().content.find("Your previous reply could not be used"), std::string::npos);
  EXPECT_NE(second.back().content.find("called no function"), std::string::npos);
  EXPECT_EQ(second.front().content.find("STRICT RULES"), std::string::npos);
  EXPECT_NE(model.requests[2].messages.front().content.find("STRICT RULES"), std::string::npos);
  EXPECT_TRUE(find_context_block(model.requests[2].messages[model.requests[2].messages.size() - 2].content));
}

TEST_F(Native, AnUnknownFunctionOrArgumentsAgainstTheSchemaAreRetried) {
  model.answers = {tool_reply({{"c1", "fly_to_the_moon", "{}"}, {"c2", "takeoff", R"({"altitude_m": "high"})"}}),
                   tool_reply({kTelemetry, kReport})};
  LlmAgent agent(model.function(), "", agent::ToolCatalog::builtin(), native());
  const agent::AgentDecision d = agent.decide(played.context(1, test::normal_net()));
  ASSERT_TRUE(d.error.empty()) << d.error;
  EXPECT_EQ(d.attempts, 2);
  const auto problems = d.attempt_log[0]["problems"];
  ASSERT_EQ(problems.size(), 2u) << problems.dump();
  EXPECT_NE(problems[0].get<std::string>().find("tool_calls/0 unknown function 'fly_to_the_moon'"), std::string::npos);
  EXPECT_NE(problems[1].get<std::string>().find("tool_calls/1 takeoff"), std::string::npos) << problems[1];
  EXPECT_NE(model.requests[1].messages.back().content.find("fly_to_the_moon"), std::string::npos);
}

TEST_F(Native, AFailureAtTheEndpointIsMarkedAndAnotherIsNot) {
  LlmCallResult down;
  down.error = "POST http://127.0.0.1:9/v1/chat/completions: connection failed";
  LlmCallResult refused = down;
  refused.http_status = 400;
  refused.error = "HTTP 400: bad request";
  model.answers = {refused, down, refused};
  LlmAgent agent(model.function(), "", agent::ToolCatalog::builtin(), native());
  const agent::AgentDecision d = agent.decide(played.context(1, test::normal_net()));
  // A refusal is corrected and retried; no HTTP answer at all ends the ladder there.
  ASSERT_EQ(d.attempt_log.size(), 2u);
  EXPECT_EQ(d.attempt_log[0]["outcome"], "call_failed");
  EXPECT_EQ(d.attempt_log[0]["endpoint_failure"], false);
  EXPECT_EQ(d.attempt_log[1]["outcome"], "call_failed");
  EXPECT_EQ(d.attempt_log[1]["endpoint_failure"], true);
}

TEST_F(Native, AStreamedCallsTokenTimesGoIntoTheAttemptLog) {
  LlmCallResult r = tool_reply({kTelemetry, kReport});
  r.streamed = true;
  r.ttft_s = 0.125;
  r.ttlt_s = 0.75;
  model.answers = {r};
  LlmAgent agent(model.function(), "", agent::ToolCatalog::builtin(), native());
  const agent::AgentDecision d = agent.decide(played.context(1, test::normal_net()));
  EXPECT_EQ(d.attempt_log[0]["streamed"], true);
  EXPECT_EQ(d.attempt_log[0]["ttft_s"], 0.125);
  EXPECT_EQ(d.attempt_log[0]["ttlt_s"], 0.75);
}

TEST(NativeMode, ParsedFromItsName) {
  EXPECT_EQ(parse_tool_mode("native"), ToolMode::kNative);
  EXPECT_EQ(parse_tool_mode("json"), ToolMode::kJson);
  EXPECT_THROW(parse_tool_mode("xml"), std::invalid_argument);
}

}  // namespace
}  // namespace a3
