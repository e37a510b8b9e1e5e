// The llm agent's prompt: the system message lists every tool and task with its schema, the
// role, the safety rules and the reply format; the user message carries the turn, n_t, the
// telemetry and a context block that rebuilds the same AgentContext; retries get stricter.
#include <gtest/gtest.h>

#include "agent/llm/context_json.hpp"
#include "agent/llm/llm_prompt.hpp"
#include "tests/agent_llm/llm_test_support.hpp"

namespace a3 {
namespace {

using agent::ToolCatalog;
using namespace agent::llm;

const ToolCatalog& tools() { return ToolCatalog::builtin(); }

TEST(LlmPrompt, SystemMessageListsEveryToolWithItsSchemaAndEveryTaskWithItsPeer) {
  const std::string s = system_prompt(tools());
  for (const auto& t : tools().tools()) {
    EXPECT_NE(s.find("- " + t.name + " (" + t.kind + "): " + t.description), std::string::npos) << t.name;
    EXPECT_NE(s.find(t.args_schema.dump()), std::string::npos) << t.name << " schema";
  }
  for (const auto& t : tools().tasks()) {
    EXPECT_NE(s.find("- " + t.task + " -> to \"" + t.to + "\""), std::string::npos) << t.task;
    EXPECT_NE(s.find(t.payload_schema.dump()), std::string::npos) << t.task << " schema";
  }
  EXPECT_NE(s.find("autonomous UAV mission agent"), std::string::npos);
  EXPECT_NE(s.find("human supervisor"), std::string::npos);
  for (const char* rule : {"geofence", "alt_bounds", "no-fly zone", "separation", "URLLC"}) {
    EXPECT_NE(s.find(rule), std::string::npos) << rule;
  }
  EXPECT_NE(s.find(reply_format_text()), std::string::npos);
  EXPECT_NE(s.find("\"intent\""), std::string::npos);
  EXPECT_EQ(s.find("STRICT RULES"), std::string::npos) << "the first attempt is not strict";
  EXPECT_NE(system_prompt(tools(), 3).find("STRICT RULES"), std::string::npos);
}

TEST(LlmPrompt, UserMessageHasTheTurnTheNetworkTheTelemetryAndEndsWithTheContextBlock) {
  const auto played = test::play_scripted("survey-field", 4);
  const auto c = played.context(5, test::hard_net());
  const std::string u = turn_prompt(c);
  EXPECT_NE(u.find("Turn 5 of at most 12"), std::string::npos) << u.substr(0, 400);
  EXPECT_NE(u.find("slice mMTC, latency 95.5 ms"), std::string::npos);
  EXPECT_NE(u.find("DEGRADED"), std::string::npos);
  EXPECT_NE(u.find("position 12.5, -3.2, altitude 59.8 m, mode hold"), std::string::npos) << u.substr(0, 800);
  EXPECT_NE(u.find("The supervisor just said: \"Understood, carry on.\""), std::string::npos);
  // The context block is last, fenced.
  const auto fence = u.rfind("```json\n");
  ASSERT_NE(fence, std::string::npos);
  EXPECT_EQ(u.substr(u.size() - 4), "```\n");
  const auto block = find_context_block(u);
  ASSERT_TRUE(block.has_value());
  EXPECT_EQ((*block)["telemetry"], played.telemetry);
  EXPECT_EQ((*block)["net"], test::hard_net());
  EXPECT_EQ((*block)["mission"]["objectives"][0]["id"], played.scenario.mission.objectives[0].id);

  const std::string normal = turn_prompt(played.context(5, test::normal_net()));
  EXPECT_NE(normal.find(": normal."), std::string::npos);
  EXPECT_EQ(normal.find("DEGRADED"), std::string::npos);
}

TEST(LlmPrompt, FirstTurnSaysNoTelemetryYet) {
  const auto played = test::play_scripted("survey-field", 0);
  const std::string u = turn_prompt(played.context(1, test::normal_net()));
  EXPECT_NE(u.find("Telemetry: none read yet"), std::string::npos);
  EXPECT_EQ(u.find("The supervisor just said"), std::string::npos);
  const auto block = find_context_block(u);
  ASSERT_TRUE(block.has_value());
  EXPECT_TRUE((*block)["telemetry"].is_null());
  EXPECT_TRUE((*block)["dialogue"].empty());
}

void expect_same_objectives(const agent::Mission& a, const agent::Mission& b) {
  ASSERT_EQ(a.objectives.size(), b.objectives.size());
  for (std::size_t i = 0; i < a.objectives.size(); ++i) {
    const auto& x = a.objectives[i];
    const auto& y = b.objectives[i];
    SCOPED_TRACE(x.id);
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.type, y.type);
    EXPECT_EQ(x.description, y.description);
    EXPECT_EQ(x.radius_m, y.radius_m);
    EXPECT_EQ(x.area, y.area);
    if (x.type == agent::ObjectiveType::kImagePoint || x.type == agent::ObjectiveType::kDelivery) {
      EXPECT_EQ(x.point, y.point);
    }
    if (x.type != agent::ObjectiveType::kDelivery && x.type != agent::ObjectiveType::kReturnAndLand) {
      EXPECT_EQ(x.altitude_m, y.altitude_m);
      EXPECT_EQ(x.sensor, y.sensor);
    }
    if (x.type == agent::ObjectiveType::kSurvey) {
      EXPECT_EQ(x.images_required, y.images_required);
    }
    if (x.type == agent::ObjectiveType::kDelivery) {
      EXPECT_EQ(x.drop_altitude_m, y.drop_altitude_m);
    }
  }
}

TEST(LlmPrompt, ContextBlockRoundTripsIntoTheSameAgentContextForEveryBuiltInScenario) {
  for (const auto& name : rigs::builtin_scenario_names()) {
    SCOPED_TRACE(name);
    const auto played = test::play_scripted(name, 6, 6, {5});
    const auto c = played.context(7, test::normal_net());
    const auto block = find_context_block(turn_prompt(c));
    ASSERT_TRUE(block.has_value());
    const RebuiltContext r = context_from_json(*block);
    const auto v = r.view(tools());
    EXPECT_EQ(v.turn_number, 7);
    EXPECT_EQ(v.max_turns, 12);
    EXPECT_EQ(v.mission_time_s, c.mission_time_s);
    EXPECT_EQ(v.net, c.net);
    EXPECT_EQ(v.last_telemetry, c.last_telemetry);
    EXPECT_EQ(v.initial_state, c.initial_state);
    EXPECT_EQ(v.airspace, c.airspace);
    EXPECT_EQ(v.tools, &tools());
    const agent::Mission& m = *v.mission;
    EXPECT_EQ(m.name, c.mission->name);
    EXPECT_EQ(m.description, c.mission->description);
    EXPECT_EQ(m.home_W_m, c.mission->home_W_m);
    EXPECT_EQ(m.cruise_altitude_m, c.mission->cruise_altitude_m);
    EXPECT_EQ(m.cruise_speed_mps, c.mission->cruise_speed_mps);
    EXPECT_EQ(m.time_limit_s, c.mission->time_limit_s);
    expect_same_objectives(*c.mission, m);
    ASSERT_EQ(v.dialogue->size(), c.dialogue->size());
    for (std::size_t i = 0; i < c.dialogue->size(); ++i) {
      const auto& x = (*c.dialogue)[i];
      const auto& y = (*v.dialogue)[i];
      EXPECT_EQ(x.number, y.number);
      EXPECT_EQ(x.speaker, y.speaker);
      EXPECT_EQ(x.intent, y.intent);
      EXPECT_EQ(x.text, y.text);
      EXPECT_EQ(x.actions, y.actions);
      EXPECT_EQ(x.obs, y.obs);
      EXPECT_EQ(x.net, y.net);
      EXPECT_EQ(x.started_s, y.started_s);
    }
  }
}

TEST(LlmPrompt, HiddenTargetsStayHidden) {
  const auto s = rigs::load_scenario("thermal-search", test::shared_dir());
  const nlohmann::json m = mission_to_json(s.mission);
  for (const auto& o : s.mission.objectives) {
    if (o.type != agent::ObjectiveType::kThermalSearch) continue;
    const std::string text = m.dump();
    EXPECT_EQ(text.find("hidden"), std::string::npos);
    EXPECT_EQ(text.find(nlohmann::json(o.hidden_target.x()).dump() + "," + nlohmann::json(o.hidden_target.y()).dump()),
              std::string::npos);
  }
}

TEST(LlmPrompt, LongDialoguesLoseTheOldestObservationsFirstAndKeepTheNewestWhole) {
  auto played = test::play_scripted("survey-field", 11);
  // Blow up every observation so that the dialogue is far over the limit.
  for (auto& t : played.dialogue) {
    for (auto& o : t.obs) {
      if (o.contains("result")) o["result"]["log"] = std::string(3000, 'x');
      if (o.contains("payload")) o["payload"]["log"] = std::string(3000, 'x');
    }
  }
  const auto c = played.context(11, test::normal_net());
  DialogueLimits limits;
  limits.max_dialogue_chars = 12'000;
  limits.keep_full_turns = 4;
  const nlohmann::json j = context_to_json(c, limits);
  ASSERT_TRUE(j.contains("dialogue_shortened"));
  const std::size_t cut = j["dialogue_shortened"].get<std::size_t>();
  EXPECT_GT(cut, 0u);
  EXPECT_LE(cut, played.dialogue.size() - 4);
  const auto& d = j["dialogue"];
  for (std::size_t i = 0; i < d.size(); ++i) {
    for (std::size_t k = 0; k < d[i]["obs"].size(); ++k) {
      const auto& o = d[i]["obs"][k];
      const bool shortened = o.dump().find("\"shortened\":true") != std::string::npos;
      EXPECT_EQ(shortened, i < cut) << "turn " << i + 1;
      // What was said and done stays.
      EXPECT_EQ(d[i]["actions"], played.dialogue[i].actions);
      EXPECT_EQ(d[i]["text"], played.dialogue[i].text);
    }
  }
  // Cut until it fits, or until only the newest turns were left whole.
  EXPECT_TRUE(d.dump().size() <= limits.max_dialogue_chars || cut == played.dialogue.size() - 4);
  // Without the limit, nothing is cut.
  EXPECT_FALSE(context_to_json(c).contains("dialogue_shortened"));
}

TEST(LlmPrompt, RetriesRestateTheFormatAndTheProblemsThenGetStrict) {
  const auto played = test::play_scripted("survey-field", 2);
  const auto c = played.context(3, test::normal_net());
  const auto first = build_turn_messages(c, tools());
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].role, "system");
  EXPECT_EQ(first[1].role, "user");

  FailedAttempt failure{"{\"intent\": \"go\", \"actions\": [{\"type\": \"mcp\", \"name\": \"fly\"}]}",
                        {"actions/0/name: unknown tool 'fly'"}};
  const auto second = build_turn_messages(c, tools(), 2, &failure);
  ASSERT_EQ(second.size(), 4u);
  EXPECT_EQ(second[2].role, "assistant");
  EXPECT_EQ(second[2].content, failure.reply);
  EXPECT_EQ(second[3].role, "user");
  EXPECT_NE(second[3].content.find("actions/0/name: unknown tool 'fly'"), std::string::npos);
  EXPECT_NE(second[3].content.find(reply_format_text()), std::string::npos);
  EXPECT_EQ(second[3].content.find("STRICT RULES"), std::string::npos);
  EXPECT_EQ(second[1].content, first[1].content) << "the turn's context is the same";

  const auto third = build_turn_messages(c, tools(), 3, &failure);
  EXPECT_NE(third[0].content.find("STRICT RULES"), std::string::npos);
  EXPECT_NE(third[3].content.find("Reply with only the JSON object"), std::string::npos);
  EXPECT_NE(third[3].content.find("do not write the supervisor's turn"), std::string::npos);
  for (const auto& t : tools().tools()) EXPECT_NE(third[3].content.find(t.name), std::string::npos);

  // A failed call has no reply to echo.
  FailedAttempt lost{"", {"HTTP 503: overloaded"}};
  const auto after_lost = build_turn_messages(c, tools(), 2, &lost);
  ASSERT_EQ(after_lost.size(), 3u);
  EXPECT_EQ(after_lost[2].role, "user");
  EXPECT_NE(after_lost[2].content.find("HTTP 503: overloaded"), std::string::npos);

  // A long reply is echoed cut, on a character boundary (the request must stay valid UTF-8).
  FailedAttempt long_reply{std::string(3999, 'a') + "\xC3\xA9" + std::string(5000, 'b'), {"reply: too long"}};
  const auto cut = build_turn_messages(c, tools(), 2, &long_reply);
  EXPECT_LT(cut[2].content.size(), 4100u);
  EXPECT_NO_THROW(nlohmann::json(cut[2].content).dump());

  EXPECT_THROW(build_turn_messages(c, tools(), 2, nullptr), std::invalid_argument);
}

TEST(LlmContext, BadBlocksAreRejectedNamingTheField) {
  const auto played = test::play_scripted("survey-field", 2);
  nlohmann::json good = context_to_json(played.context(3, test::normal_net()));
  auto expect_error = [](nlohmann::json j, const std::string& where) {
    try {
      context_from_json(j);
      ADD_FAILURE() << "accepted: " << where;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
  };
  auto j = good;
  j["a3_context"] = 2;
  expect_error(j, "context/a3_context");
  j = good;
  j["dialogue"][1]["actions"] = "none";
  expect_error(j, "context/dialogue/1/actions: expected an array");
  j = good;
  j["dialogue"][0]["speaker"] = "assistant";
  expect_error(j, "context/dialogue/0/speaker");
  j = good;
  j["mission"]["objectives"][0]["type"] = "loiter";
  expect_error(j, "context/mission/objectives/0/type: unknown objective type 'loiter'");
  j = good;
  j["mission"].erase("home");
  expect_error(j, "context/mission/home: missing");
  j = good;
  j.erase("turn");
  expect_error(j, "context/turn: missing");
  EXPECT_NO_THROW(context_from_json(good));

  EXPECT_FALSE(find_context_block("no block here").has_value());
  EXPECT_FALSE(find_context_block("```json\n{\"intent\": \"x\"}\n```").has_value());
  EXPECT_TRUE(find_context_block("prose {\"a\": 1} then ```json\n" + good.dump() + "\n```").has_value());
}

}  // namespace
}  // namespace a3
