// LlmClient and tool calling: requests carry tools, tool_choice, assistant tool_calls and tool
// messages as OpenAI defines them; an answer of tool_calls with null content is an answer; a
// provider that refuses max_tokens gets max_completion_tokens (remembered), one that refuses
// tool_choice gets none; the refusal is read from error.param before the text.
#include <gtest/gtest.h>

#include "agent/llm/http_chat_completion.hpp"
#include "agent/llm/llm_client.hpp"
#include "agent/llm/request_fallbacks.hpp"
#include "tests/agent_llm_client/scripted_openai_server.hpp"

namespace {

using namespace a3::agent::llm;
using a3::test::RecordedRequest;
using a3::test::ScriptedOpenAiServer;
using a3::test::ScriptedReply;
using nlohmann::json;

LlmEndpoint endpoint_for(const std::string& base_url) {
  LlmEndpoint e;
  e.base_url = base_url;
  e.model = "tool-model";
  e.connect_timeout_s = 2.0;
  e.total_timeout_s = 5.0;
  e.max_retries = 0;
  e.max_tokens = 321;
  return e;
}

const json kTools = json::array({{{"type", "function"},
                                  {"function",
                                   {{"name", "read_telemetry"},
                                    {"description", "Reads the vehicle's state."},
                                    {"parameters", {{"type", "object"}, {"properties", json::object()}}}}}}});

std::string tool_call_body(const json& calls, const json& content = nullptr) {
  return json({{"id", "chatcmpl-t"},
               {"object", "chat.completion"},
               {"model", "tool-model"},
               {"choices",
                {{{"index", 0},
                  {"message", {{"role", "assistant"}, {"content", content}, {"tool_calls", calls}}},
                  {"finish_reason", "tool_calls"}}}},
               {"usage", {{"prompt_tokens", 30}, {"completion_tokens", 9}, {"total_tokens", 39}}}})
      .dump();
}

json call_json(const std::string& id, const std::string& name, const std::string& arguments) {
  return {{"id", id}, {"type", "function"}, {"function", {{"name", name}, {"arguments", arguments}}}};
}

ChatRequest request_with_history() {
  ChatRequest r;
  r.messages = {{"system", "Fly."},
                {"user", "Turn 1."},
                {"assistant", "", {{"call_a", "read_telemetry", "{}"}, {"call_b", "navigate_to", R"({"x":1})"}}},
                {"tool", R"({"status":"ok"})", {}, "call_a"},
                {"tool", R"({"status":"moving"})", {}, "call_b"},
                {"user", "Turn 3."}};
  r.tools = kTools;
  r.tool_choice = "required";
  return r;
}

TEST(LlmClientTools, ParallelToolCallsWithNullContentAreAnAnswer) {
  const json calls = {call_json("call_1", "read_telemetry", "{}"),
                      call_json("call_2", "navigate_to", R"({"x": 10.5, "y": -2})")};
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{200, tool_call_body(calls)}}));
  LlmClient client(endpoint_for(server.base_url()));
  const LlmCallResult r = client.send(request_with_history());
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.content, "");
  EXPECT_EQ(r.finish_reason, "tool_calls");
  ASSERT_EQ(r.tool_calls.size(), 2u);
  EXPECT_EQ(r.tool_calls[0].id, "call_1");
  EXPECT_EQ(r.tool_calls[0].name, "read_telemetry");
  EXPECT_EQ(r.tool_calls[0].arguments, "{}");
  EXPECT_EQ(r.tool_calls[1].id, "call_2");
  EXPECT_EQ(r.tool_calls[1].name, "navigate_to");
  EXPECT_EQ(r.tool_calls[1].arguments, R"({"x": 10.5, "y": -2})");
  EXPECT_EQ(r.usage.total_tokens, 39);
}

TEST(LlmClientTools, TheRequestCarriesToolsToolChoiceToolCallsAndToolMessagesAsOpenAiDefines) {
  ScriptedOpenAiServer server(
      ScriptedOpenAiServer::sequence({{200, tool_call_body(json::array({call_json("c", "read_telemetry", "{}")}))}}));
  LlmEndpoint e = endpoint_for(server.base_url());
  e.json_output = true;  // never together with tools
  LlmClient client(e);
  const LlmCallResult r = client.send(request_with_history());
  ASSERT_TRUE(r.ok) << r.error;
  const json body = server.requests().at(0).body;
  EXPECT_EQ(body["tools"], kTools);
  EXPECT_EQ(body["tool_choice"], "required");
  EXPECT_FALSE(body.contains("response_format"));
  EXPECT_EQ(body["max_tokens"], 321);
  EXPECT_FALSE(body.contains("stream"));
  const json& m = body["messages"];
  ASSERT_EQ(m.size(), 6u);
  EXPECT_TRUE(m[2]["content"].is_null());
  EXPECT_EQ(m[2]["role"], "assistant");
  EXPECT_EQ(m[2]["tool_calls"][1], call_json("call_b", "navigate_to", R"({"x":1})"));
  EXPECT_EQ(m[3], json({{"role", "tool"}, {"content", R"({"status":"ok"})"}, {"tool_call_id", "call_a"}}));
  EXPECT_EQ(m[4]["tool_call_id"], "call_b");
  EXPECT_FALSE(m[5].contains("tool_call_id"));
  EXPECT_FALSE(m[5].contains("tool_calls"));
}

TEST(LlmClientTools, AToolCallWithoutAFunctionNameIsAClearError) {
  const json calls = {{{"id", "c"}, {"type", "function"}, {"function", {{"arguments", "{}"}}}}};
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{200, tool_call_body(calls)}}));
  LlmClient client(endpoint_for(server.base_url()));
  const LlmCallResult r = client.send(request_with_history());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("choices[0].message.tool_calls/0: no function.name"), std::string::npos) << r.error;
}

TEST(LlmClientTools, ArgumentsGivenAsAnObjectAreKeptAsTheirJsonText) {
  const json calls = {{{"id", "c"}, {"function", {{"name", "navigate_to"}, {"arguments", {{"x", 3}}}}}}};
  ScriptedOpenAiServer server(ScriptedOpenAiServer::sequence({{200, tool_call_body(calls, "Going.")}}));
  LlmClient client(endpoint_for(server.base_url()));
  const LlmCallResult r = client.send(request_with_history());
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.content, "Going.");
  ASSERT_EQ(r.tool_calls.size(), 1u);
  EXPECT_EQ(json::parse(r.tool_calls[0].arguments), json({{"x", 3}}));
}

// OpenAI's answer to max_tokens for its reasoning models.
const char* kMaxTokensRefusal =
    R"({"error":{"message":"Unsupported parameter: 'max_tokens' is not supported with this model. Use 'max_completion_tokens' instead.","type":"invalid_request_error","param":"max_tokens","code":"unsupported_parameter"}})";

TEST(LlmClientTools, MaxTokensRefusedIsSentAsMaxCompletionTokensForTheClientsLife) {
  ScriptedOpenAiServer server([](const RecordedRequest& req, int) {
    if (req.body.contains("max_tokens")) return ScriptedReply{400, kMaxTokensRefusal};
    return ScriptedReply{200, tool_call_body(json::array({call_json("c", "read_telemetry", "{}")}))};
  });
  LlmEndpoint e = endpoint_for(server.base_url());
  e.json_output = true;
  LlmClient client(e);
  const LlmCallResult first = client.chat({{"user", "hi"}});
  ASSERT_TRUE(first.ok) << first.error;
  EXPECT_EQ(first.http_attempts, 2);
  ASSERT_EQ(first.attempts.size(), 2u);
  EXPECT_NE(first.attempts[0].error.find("sending max_completion_tokens instead of max_tokens"), std::string::npos)
      << first.attempts[0].error;
  EXPECT_TRUE(client.refused_parameters().max_tokens);
  EXPECT_FALSE(client.response_format_dropped()) << "the hint names max_completion_tokens, not response_format";
  const LlmCallResult second = client.chat({{"user", "again"}});
  ASSERT_TRUE(second.ok) << second.error;
  EXPECT_EQ(second.http_attempts, 1);
  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 3u);
  EXPECT_EQ(requests[1].body["max_completion_tokens"], 321);
  EXPECT_FALSE(requests[1].body.contains("max_tokens"));
  EXPECT_TRUE(requests[1].body.contains("response_format"));
  EXPECT_EQ(requests[2].body["max_completion_tokens"], 321);
}

TEST(LlmClientTools, ToolChoiceRefusedIsDroppedAndTheToolsStay) {
  ScriptedOpenAiServer server([](const RecordedRequest& req, int) {
    if (req.body.contains("tool_choice")) {
      return ScriptedReply{400, R"({"error":{"message":"tool_choice \"required\" is not supported by this server"}})"};
    }
    return ScriptedReply{200, tool_call_body(json::array({call_json("c", "read_telemetry", "{}")}))};
  });
  LlmClient client(endpoint_for(server.base_url()));
  const LlmCallResult r = client.send(request_with_history());
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(client.refused_parameters().tool_choice);
  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_FALSE(requests[1].body.contains("tool_choice"));
  EXPECT_EQ(requests[1].body["tools"], kTools);
}

TEST(LlmClientTools, AnUnrelated400ChangesNothing) {
  ScriptedOpenAiServer server(
      ScriptedOpenAiServer::sequence({{400, R"({"error":{"message":"messages: too long","param":"messages"}})"}}));
  LlmClient client(endpoint_for(server.base_url()));
  const LlmCallResult r = client.send(request_with_history());
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(server.requests().size(), 1u);
  EXPECT_FALSE(client.refused_parameters().tool_choice);
  EXPECT_FALSE(client.refused_parameters().max_tokens);
}

TEST(RequestFallbacks, ErrorParamWinsOverTheTextAndOnlySentParametersAreAdapted) {
  SentParameters sent;
  sent.response_format = true;
  sent.max_tokens = true;
  RefusedParameters refused;
  // The text names response_format too, but the param says which one was refused.
  const std::string body =
      R"({"error":{"message":"max_tokens is not supported with response_format here","param":"max_tokens"}})";
  EXPECT_EQ(adapt_to_refusal(400, body, sent, refused), "sending max_completion_tokens instead of max_tokens");
  EXPECT_TRUE(refused.max_tokens);
  EXPECT_FALSE(refused.response_format);
  // Not sent: nothing to adapt.
  RefusedParameters none;
  EXPECT_EQ(adapt_to_refusal(400, R"({"error":{"message":"tool_choice is not supported"}})", sent, none), "");
  EXPECT_FALSE(none.tool_choice);
  // Not a refusal status.
  EXPECT_EQ(adapt_to_refusal(500, R"(response_format)", sent, none), "");
  // Text only, 422.
  EXPECT_EQ(adapt_to_refusal(422, "unknown field response_format", sent, none), "dropping response_format");
}

TEST(EndpointFailure, NoAnswerAuthNotFoundThrottleAndServerErrorsAreTheEndpoints) {
  LlmCallResult r;
  for (int status : {0, 401, 403, 404, 408, 429, 500, 503}) {
    r.http_status = status;
    EXPECT_TRUE(is_endpoint_failure(r)) << status;
  }
  for (int status : {400, 413, 422}) {
    r.http_status = status;
    EXPECT_FALSE(is_endpoint_failure(r)) << status;
  }
  r.ok = true;
  r.http_status = 0;
  EXPECT_FALSE(is_endpoint_failure(r));
}

}  // namespace
