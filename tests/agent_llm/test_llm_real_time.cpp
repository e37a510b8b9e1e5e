// A closed-loop `--agent llm` episode in real time, native tool calling and json: the llm agent
// asks `serve-model --responder scripted` (a ModelServer on loopback, 0.25 s per answer) while
// the world flies on; traffic-conflict at --rtf 4 is flown to success with α³ >= 0.9 in both
// modes, every agent turn answered at its first attempt, and each turn's think time at least the
// server's wall latency in simulated seconds at the rate the world ran (it passed in the world,
// not outside it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "tests/agent_llm/scripted_server.hpp"
#include "tests/rigs/real_time_support.hpp"

namespace a3 {
namespace {

constexpr double kServerLatency_s = 0.25;
// 4, the rate the main job flies at: these tests run alone (SERIAL under `ctest -j`), where the
// lockstep rig keeps --rtf 4 on this project's 2-core build machine with margin (it keeps it
// under two busy loops in tests/rigs/test_lockstep_rig.cpp), so the test checks the agent's
// latency, not the host's speed.
constexpr double kRealTimeFactor = 4.0;


void fly_in_real_time(const std::string& tools_mode) {
  for (const char* name : {"A3_LLM_API_KEY", "A3_LLM_API_KEY_FILE", "OPENAI_API_KEY", "A3_LLM_PROVIDER"}) {
    ::unsetenv(name);
  }
  test::ScriptedServer s("fixed:" + std::to_string(kServerLatency_s));
  rigs::RunOptions o = test::virtual_run("traffic-conflict", "llm-real-time-" + tools_mode);
  o.runtime = rigs::Runtime::kReal;
  o.real_time_factor = kRealTimeFactor;
  o.agent = "llm";
  o.llm_tools = tools_mode;
  o.llm_base_url = s.server.base_url();
  o.llm_model = "scripted-policy";
  const rigs::RunResult r = test::run(o);

  ASSERT_EQ(r.status, "completed") << r.episode["_rig"].dump(1).substr(0, 3000);
  EXPECT_TRUE(r.episode["success"].get<bool>());
  const test::Scored score = test::score(r.episode);
  ASSERT_TRUE(score.valid) << score.problems;
  EXPECT_GE(score.pillars.alpha3, 0.9);
  // Simulated time runs at the requested factor, slower where lockstep waited on a loaded host:
  // the slowest 1 s window bounds how little world time a call's wall time can be.
  const double worst_rtf = r.episode["_rig"]["realtime"]["rtf"]["worst_window"].get<double>();
  ASSERT_GT(worst_rtf, 0.5 * kRealTimeFactor) << "the run did not keep real time";
  const double min_think_s = 0.9 * kServerLatency_s * std::min(kRealTimeFactor, worst_rtf);
  int agent_turns = 0;
  for (const auto& rig : r.episode["_rig"]["turns"]) {
    if (rig["speaker"] != "agent") continue;
    ++agent_turns;
    SCOPED_TRACE("turn " + std::to_string(rig["turn"].get<int>()));
    EXPECT_EQ(rig["attempts"], 1);
    EXPECT_EQ(rig["attempt_log"][0]["outcome"], "ok");
    EXPECT_EQ(rig["attempt_log"][0]["tool_mode"], tools_mode);
    EXPECT_GE(rig["think_time_s"].get<double>(), min_think_s)
        << "the model's wall time passed in the simulated world (worst 1 s window: x" << worst_rtf << ")";
  }
  EXPECT_GE(agent_turns, 4);
}

TEST(LlmRealTime, TrafficConflictFlownNativeAgainstTheScriptedResponder) {
  A3_REQUIRE_MULTICAST();
  fly_in_real_time("native");
}

TEST(LlmRealTime, TrafficConflictFlownJsonAgainstTheScriptedResponder) {
  A3_REQUIRE_MULTICAST();
  fly_in_real_time("json");
}

}  // namespace
}  // namespace a3
