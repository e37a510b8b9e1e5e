// A closed-loop `--agent llm` episode in virtual time: the llm agent asks a ModelServer on
// loopback whose scripted responder answers with the rig's scripted policy. The mission succeeds
// as the scripted agent's does, each agent turn's measured latency (the server's fixed 0.25 s
// plus the HTTP exchange) is charged to simulated time before its actions leave, and the
// episode records per turn the attempts, the usage and the latency, and in _meta their sums and
// the model and provider.
#include <gtest/gtest.h>

#include <cstdlib>

#include "tests/agent_llm/scripted_server.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3 {
namespace {


constexpr double kServerLatency_s = 0.25;

using test::ScriptedServer;

TEST(LlmClosedLoop, SurveyFieldFlownByTheLlmAgentAgainstTheScriptedResponder) {
  // Keys or endpoints of the user's environment play no part here.
  ::unsetenv("A3_LLM_API_KEY");
  ::unsetenv("A3_LLM_API_KEY_FILE");
  ::unsetenv("OPENAI_API_KEY");
  ::unsetenv("A3_LLM_PROVIDER");
  ScriptedServer s("fixed:" + std::to_string(kServerLatency_s));

  rigs::RunOptions o = test::virtual_run("survey-field", "llm-closed-loop");
  o.agent = "llm";
  o.llm_tools = "json";  // the paper's protocol: the prompt carries the catalogue as text
  o.llm_base_url = s.server.base_url();
  o.llm_model = "scripted-policy";
  const rigs::RunResult llm = test::run(o);

  rigs::RunOptions scripted_options = test::virtual_run("survey-field", "llm-closed-loop-reference");
  const rigs::RunResult scripted = test::run(scripted_options);

  ASSERT_EQ(llm.status, "completed") << llm.episode["_rig"].dump(1).substr(0, 3000);
  EXPECT_TRUE(llm.episode["success"].get<bool>());
  EXPECT_EQ(llm.episode["success"], scripted.episode["success"]);
  const test::Scored score = test::score(llm.episode);
  ASSERT_TRUE(score.valid) << score.problems;
  EXPECT_EQ(score.pillars.to, 1.0);
  EXPECT_EQ(score.pillars.sp, 1.0);

  // The same plan as the scripted agent's, turn by turn.
  const auto& dialogue = llm.episode["dialogue"];
  const auto& reference = scripted.episode["dialogue"];
  std::vector<std::string> llm_intents, scripted_intents;
  for (const auto& t : dialogue) {
    if (t["speaker"] == "agent") llm_intents.push_back(t["intent"]);
  }
  for (const auto& t : reference) {
    if (t["speaker"] == "agent") scripted_intents.push_back(t["intent"]);
  }
  EXPECT_EQ(llm_intents, scripted_intents);

  // Per agent turn: one attempt, usage, the latency charged before the actions left.
  int64_t prompt = 0, completion = 0, total = 0;
  double latency_sum_s = 0.0;
  int agent_turns = 0;
  for (const auto& rig : llm.episode["_rig"]["turns"]) {
    if (rig["speaker"] != "agent") continue;
    ++agent_turns;
    SCOPED_TRACE("turn " + std::to_string(rig["turn"].get<int>()));
    EXPECT_EQ(rig["attempts"], 1);
    ASSERT_TRUE(rig.contains("attempt_log"));
    ASSERT_EQ(rig["attempt_log"].size(), 1u);
    EXPECT_EQ(rig["attempt_log"][0]["outcome"], "ok");
    EXPECT_EQ(rig["attempt_log"][0]["http_status"], 200);
    const auto& u = rig["usage"];
    EXPECT_GT(u.value("prompt_tokens", 0), 2000) << "the prompt carries the catalogue and the context";
    EXPECT_GT(u.value("completion_tokens", 0), 5);
    prompt += u.value("prompt_tokens", int64_t{0});
    completion += u.value("completion_tokens", int64_t{0});
    total += u.value("total_tokens", int64_t{0});
    const double think = rig["think_time_s"].get<double>();
    EXPECT_GE(think, kServerLatency_s) << "the measured latency includes the server's wait";
    EXPECT_LT(think, 30.0);
    EXPECT_NEAR(rig["decided_s"].get<double>() - rig["started_s"].get<double>(), think, 1e-3)
        << "the latency passed in simulated time before the actions left";
    latency_sum_s += think;
  }
  EXPECT_EQ(agent_turns, static_cast<int>(llm_intents.size()));
  EXPECT_EQ(s.server.stats().answered, static_cast<uint64_t>(agent_turns));

  const auto& meta = llm.episode["_meta"];
  EXPECT_EQ(meta["model"], "scripted-policy");
  EXPECT_EQ(meta["provider"], "local");
  EXPECT_EQ(meta["attempts_used"], 1);
  EXPECT_EQ(meta["usage"]["prompt_tokens"], prompt);
  EXPECT_EQ(meta["usage"]["completion_tokens"], completion);
  EXPECT_EQ(meta["usage"]["total_tokens"], total);
  EXPECT_EQ(total, prompt + completion);
  EXPECT_NEAR(meta["gen_time_s"].get<double>(), latency_sum_s, 1e-9);
  EXPECT_EQ(s.server.stats().prompt_tokens, prompt);
  // The scripted agent declares no latency and no usage: the difference is the LLM's.
  EXPECT_EQ(scripted.episode["_meta"]["usage"]["total_tokens"], 0);
}

TEST(LlmClosedLoop, AMissingEndpointIsAClearErrorBeforeAnythingFlies) {
  ::unsetenv("A3_LLM_BASE_URL");
  ::unsetenv("A3_LLM_MODEL");
  rigs::RunOptions o = test::virtual_run("survey-field", "llm-no-endpoint");
  o.agent = "llm";
  try {
    test::run(o);
    FAIL() << "ran without an endpoint";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("A3_LLM_BASE_URL"), std::string::npos) << e.what();
  }
  o.llm_base_url = "http://127.0.0.1:9/v1";
  try {
    test::run(o);
    FAIL() << "ran without a model";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("A3_LLM_MODEL"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace a3
