// The scripted responder: from the llm agent's prompt alone (no state kept between requests) it
// answers every turn exactly as a live scripted agent does — detours, traffic alerts, network
// adaptation included — with token usage estimated from characters; a request without the
// context block gets a generic answer; a broken block is a clear 400-style error.
#include <gtest/gtest.h>

#include "agent/llm/llm_prompt.hpp"
#include "agent/llm/llm_reply.hpp"
#include "agent/model_server/model_server.hpp"
#include "agent/model_server/scripted_responder.hpp"
#include "tests/agent_llm/llm_test_support.hpp"

namespace a3 {
namespace {

using agent::model_server::ScriptedResponder;

nlohmann::json request_for(const std::vector<agent::llm::ChatMessage>& messages) {
  nlohmann::json m = nlohmann::json::array();
  for (const auto& x : messages) m.push_back({{"role", x.role}, {"content", x.content}});
  return {{"model", "scripted"}, {"messages", m}, {"temperature", 0}};
}

// Every agent turn of a played dialogue, asked of a fresh responder, gets the live agent's decision.
void expect_same_as_live(const std::string& scenario, int turns, int alert_turn, std::vector<int> hard) {
  SCOPED_TRACE(scenario);
  // Play all the turns once to know the dialogue; then ask for each agent turn with its prefix.
  const auto full = test::play_scripted(scenario, turns, alert_turn, hard);
  std::size_t agent_turn = 0;
  for (int k = 1; k <= turns; k += 2, ++agent_turn) {
    SCOPED_TRACE("turn " + std::to_string(k));
    test::PlayedContext prefix = full;
    prefix.dialogue.resize(static_cast<std::size_t>(k - 1));
    prefix.telemetry = nullptr;
    for (const auto& t : prefix.dialogue) {
      for (const auto& o : t.obs) {
        if (o.value("tool", "") == "read_telemetry") prefix.telemetry = o["result"];
      }
    }
    const bool is_hard = std::find(hard.begin(), hard.end(), k) != hard.end();
    const auto c = prefix.context(k, is_hard ? test::hard_net() : test::normal_net());
    ScriptedResponder responder;
    const auto reply = responder.respond(request_for(agent::llm::build_turn_messages(c, agent::ToolCatalog::builtin())));
    const auto parsed = agent::llm::parse_reply(reply.content, agent::ToolCatalog::builtin());
    ASSERT_TRUE(parsed.ok()) << parsed.problems_text() << "\n" << reply.content;
    const auto& live = full.decisions[agent_turn];
    EXPECT_EQ(parsed.intent, live.intent);
    EXPECT_EQ(parsed.text, live.text);
    EXPECT_EQ(parsed.actions, live.actions);
  }
}

TEST(ScriptedResponder, AnswersEveryTurnAsTheLiveScriptedAgentDoes) {
  expect_same_as_live("survey-field", 11, -1, {});
  // A route around a no-fly zone from the pre-flight path_plan, flown there and back.
  expect_same_as_live("nfz-detour", 11, -1, {});
  // A traffic alert from the supervisor, and a degraded link on two agent turns.
  expect_same_as_live("traffic-conflict", 11, 4, {5, 7});
  expect_same_as_live("thermal-search", 11, -1, {3});
  expect_same_as_live("parcel-delivery", 9, -1, {});
  expect_same_as_live("bridge-inspection", 11, -1, {9});
}

TEST(ScriptedResponder, TheLiveDialogueReallyExercisesTheBranches) {
  // Guards the test above against passing on trivial dialogues.
  const auto detour = test::play_scripted("nfz-detour", 11);
  bool route = false;
  for (const auto& d : detour.decisions) {
    for (const auto& a : d.actions) route |= a.value("name", "") == "navigate_to";
  }
  EXPECT_TRUE(route);
  const auto traffic = test::play_scripted("traffic-conflict", 11, 4, {5, 7});
  bool slice = false, avoidance = false;
  for (const auto& a : traffic.decisions[2].actions) {
    slice |= a.value("name", "") == "switch_network_slice";
    avoidance |= a.value("task", "") == "collision_avoidance";
  }
  EXPECT_TRUE(slice);
  EXPECT_TRUE(avoidance);
}

TEST(ScriptedResponder, UsageIsEstimatedAtFourCharactersPerToken) {
  const auto played = test::play_scripted("survey-field", 2);
  const auto messages = agent::llm::build_turn_messages(played.context(3, test::normal_net()), agent::ToolCatalog::builtin());
  const auto request = request_for(messages);
  ScriptedResponder responder;
  const auto reply = responder.respond(request);
  const int64_t prompt = reply.usage["prompt_tokens"].get<int64_t>();
  const int64_t completion = reply.usage["completion_tokens"].get<int64_t>();
  std::size_t chars = 0;
  for (const auto& m : messages) chars += m.content.size();
  // Code points vs bytes differ a little (a few non-ASCII characters in the prompt).
  EXPECT_NEAR(static_cast<double>(prompt), chars / 4.0, chars / 400.0 + 1.0);
  EXPECT_EQ(completion, static_cast<int64_t>((reply.content.size() + 3) / 4));
  EXPECT_EQ(reply.usage["total_tokens"].get<int64_t>(), prompt + completion);
  EXPECT_FALSE(reply.latency_s.has_value()) << "the server's latency model decides";
}

TEST(ScriptedResponder, TheLatestUserMessageWithABlockIsUsedAfterACorrection) {
  const auto played = test::play_scripted("survey-field", 2);
  const auto c = played.context(3, test::normal_net());
  agent::llm::FailedAttempt failure{"nonsense", {"reply: no JSON object in the reply"}};
  ScriptedResponder responder;
  const auto retry = responder.respond(request_for(agent::llm::build_turn_messages(c, agent::ToolCatalog::builtin(), 3, &failure)));
  const auto first = responder.respond(request_for(agent::llm::build_turn_messages(c, agent::ToolCatalog::builtin())));
  EXPECT_EQ(retry.content, first.content);
  // Parts-style content (a list of {"type": "text", "text": ...}) works too.
  auto request = request_for(agent::llm::build_turn_messages(c, agent::ToolCatalog::builtin()));
  const std::string text = request["messages"][1]["content"];
  request["messages"][1]["content"] = {{{"type", "text"}, {"text", text}}};
  EXPECT_EQ(responder.respond(request).content, first.content);
}

TEST(ScriptedResponder, RequestsWithoutAContextBlockGetAGenericAnswerAndBrokenBlocksAre400Style) {
  ScriptedResponder responder;
  const nlohmann::json plain = {{"model", "scripted"},
                                {"messages", {{{"role", "system"}, {"content", "You are helpful."}},
                                              {{"role", "user"}, {"content", "Write a UAV episode as JSON."}}}}};
  // Any OpenAI client works against it (issue 13): a short text, not a refusal.
  EXPECT_NE(responder.respond(plain).content.find("scripted responder"), std::string::npos);
  EXPECT_THROW(responder.respond(nlohmann::json::object()), std::invalid_argument);
  EXPECT_THROW(responder.respond({{"messages", "hi"}}), std::invalid_argument);
  // A block that is not a usable context names the field.
  const nlohmann::json broken = {{"messages", {{{"role", "user"}, {"content", R"(```json
{"a3_context": 1, "turn": 3, "max_turns": 12, "mission": {"home": [0, 0]}, "dialogue": []}
```)"}}}}};
  try {
    responder.respond(broken);
    FAIL() << "answered a broken block";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("context/mission/home"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace a3
