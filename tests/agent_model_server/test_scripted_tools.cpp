// The scripted responder with `tools`: the live scripted agent's decision as tool calls (one per
// action, then report_turn with intent and text), the text as content when report_turn is not
// offered, tool_choice "none" keeping the JSON text protocol, functions the catalog lacks
// refused naming the field; and the generic answer to clients that are not a3rig.
#include <gtest/gtest.h>

#include "agent/llm/llm_prompt.hpp"
#include "agent/llm/llm_reply.hpp"
#include "agent/model_server/model_server.hpp"
#include "agent/model_server/reply_shaping.hpp"
#include "agent/model_server/schema_instance.hpp"
#include "agent/model_server/scripted_responder.hpp"
#include "tests/agent_llm/llm_test_support.hpp"

namespace a3 {
namespace {

namespace ms = agent::model_server;
using nlohmann::json;
const agent::ToolCatalog& catalog() { return agent::ToolCatalog::builtin(); }

json request_for(const agent::AgentContext& c, const json& tools, const json& tool_choice = nullptr) {
  json m = json::array();
  for (const auto& x : agent::llm::build_turn_messages(c, catalog())) m.push_back({{"role", x.role}, {"content", x.content}});
  json r = {{"model", "scripted"}, {"messages", m}};
  if (!tools.is_null()) r["tools"] = tools;
  if (!tool_choice.is_null()) r["tool_choice"] = tool_choice;
  return r;
}

// The request as the server checks and shapes it, then answered.
ms::ResponderReply answer(const json& request) {
  if (auto e = ms::chat_request_error(request)) ADD_FAILURE() << e->message;
  ms::ScriptedResponder responder;
  ms::ResponderReply reply = responder.respond(request);
  ms::shape_reply(reply, ms::chat_options(request), "0");
  return reply;
}

json without(const std::string& name) {
  json tools = json::array();
  for (const auto& t : catalog().openai_tools()) {
    if (t["function"]["name"] != name) tools.push_back(t);
  }
  return tools;
}

TEST(ScriptedTools, EveryAgentTurnIsTheLiveDecisionAsToolCallsEndingWithReportTurn) {
  const auto played = test::play_scripted("survey-field", 7);
  std::size_t agent_turn = 0;
  for (int k = 1; k <= 7; k += 2, ++agent_turn) {
    SCOPED_TRACE("turn " + std::to_string(k));
    test::PlayedContext prefix = played;
    prefix.dialogue.resize(static_cast<std::size_t>(k - 1));
    const auto reply = answer(request_for(prefix.context(k, test::normal_net()), catalog().openai_tools()));
    const auto& live = played.decisions[agent_turn];
    ASSERT_EQ(reply.tool_calls.size(), live.actions.size() + 1);
    EXPECT_EQ(reply.finish_reason, "tool_calls");
    EXPECT_EQ(reply.content, "");  // sent as null
    json actions = json::array();
    for (std::size_t i = 0; i + 1 < reply.tool_calls.size(); ++i) {
      const auto& call = reply.tool_calls[i];
      EXPECT_EQ(call.id, "call_0_" + std::to_string(i));
      const auto as_action = catalog().action_from_call(call.name, call.arguments);
      ASSERT_EQ(as_action.problem, "") << call.name << " " << call.arguments;
      actions.push_back(as_action.action);
    }
    EXPECT_EQ(actions, json(live.actions));
    const auto& report = reply.tool_calls.back();
    EXPECT_EQ(report.name, "report_turn");
    EXPECT_EQ(json::parse(report.arguments), json({{"intent", live.intent}, {"text", live.text}}));
  }
}

TEST(ScriptedTools, WithoutReportTurnTheTextIsTheContent) {
  const auto played = test::play_scripted("survey-field", 1);
  test::PlayedContext prefix = played;
  prefix.dialogue.clear();
  const auto reply = answer(request_for(prefix.context(1, test::normal_net()), without("report_turn")));
  EXPECT_EQ(reply.content, played.decisions[0].text);
  EXPECT_EQ(reply.tool_calls.size(), played.decisions[0].actions.size());
  for (const auto& c : reply.tool_calls) EXPECT_NE(c.name, "report_turn");
}

TEST(ScriptedTools, ToolChoiceNoneKeepsTheJsonTextProtocolAndNamedKeepsOnlyThatFunction) {
  const auto played = test::play_scripted("survey-field", 1);
  test::PlayedContext prefix = played;
  prefix.dialogue.clear();
  const auto c = prefix.context(1, test::normal_net());
  const auto none = answer(request_for(c, catalog().openai_tools(), "none"));
  EXPECT_TRUE(none.tool_calls.empty());
  const auto parsed = agent::llm::parse_reply(none.content, catalog());
  ASSERT_TRUE(parsed.ok()) << parsed.problems_text();
  EXPECT_EQ(parsed.intent, played.decisions[0].intent);

  const json named = {{"type", "function"}, {"function", {{"name", "report_turn"}}}};
  const auto report_only = answer(request_for(c, catalog().openai_tools(), named));
  ASSERT_EQ(report_only.tool_calls.size(), 1u);
  EXPECT_EQ(report_only.tool_calls[0].name, "report_turn");
}

TEST(ScriptedTools, AFunctionTheCatalogLacksIsRefusedNamingTheField) {
  const auto played = test::play_scripted("survey-field", 1);
  test::PlayedContext prefix = played;
  prefix.dialogue.clear();
  json tools = catalog().openai_tools();
  tools.push_back({{"type", "function"}, {"function", {{"name", "fly_to_mars"}, {"parameters", json::object()}}}});
  ms::ScriptedResponder responder;
  try {
    responder.respond(request_for(prefix.context(1, test::normal_net()), tools));
    ADD_FAILURE() << "fly_to_mars was accepted";
  } catch (const ms::BadRequest& e) {
    const std::string param = "tools[" + std::to_string(tools.size() - 1) + "].function.name";
    EXPECT_EQ(e.param(), param);
    EXPECT_NE(std::string(e.what()).find("'fly_to_mars' is not a function the scripted responder can call"),
              std::string::npos) << e.what();
  }
}

TEST(ScriptedTools, ClientsThatAreNotA3rigGetAGenericAnswer) {
  const json schema = json::parse(R"({"type":"object","properties":{"city":{"type":"string","minLength":8},
    "days":{"type":"integer","minimum":3,"maximum":5}},"required":["city","days"]})");
  const json tools = {{{"type", "function"}, {"function", {{"name", "weather"}, {"parameters", schema}}}},
                      {{"type", "function"}, {"function", {{"name", "time"}}}}};
  const json plain = {{"model", "gpt-4o"}, {"messages", {{{"role", "user"}, {"content", "What is the weather?"}}}}};
  json with_tools = plain;
  with_tools["tools"] = tools;

  const auto call = answer(with_tools);
  ASSERT_EQ(call.tool_calls.size(), 1u);
  EXPECT_EQ(call.tool_calls[0].name, "weather");
  EXPECT_EQ(ms::schema_problems(schema, json::parse(call.tool_calls[0].arguments)), "") << call.tool_calls[0].arguments;
  EXPECT_EQ(call.finish_reason, "tool_calls");

  json named = with_tools;
  named["tool_choice"] = {{"type", "function"}, {"function", {{"name", "time"}}}};
  EXPECT_EQ(answer(named).tool_calls.at(0).name, "time");

  const auto text = answer(plain);
  EXPECT_TRUE(text.tool_calls.empty());
  EXPECT_NE(text.content.find("scripted responder"), std::string::npos);
  EXPECT_GT(text.usage["total_tokens"].get<int>(), 0);
}

}  // namespace
}  // namespace a3
