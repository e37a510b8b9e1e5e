// Closed-loop `--agent llm` runs in virtual time, native tool calling and json: against
// `serve-model --responder scripted` (a ModelServer on loopback, which answers a request with
// tools by tool calls only) every built-in scenario is flown to success with α³ >= 0.9 in both
// modes; against a server that only ever answers with text, native mode fails every agent turn
// with a clear per-turn error and the run ends agent_failed (exit status 6), its episode still a
// valid α³-Bench episode; against an endpoint that is gone, the run ends endpoint_failed (exit
// status 7) after 2 agent turns, the episode written with that status. A streamed native run
// records each turn's time to the first and the last token; the `a3rig run` program flies
// native by default and its episode passes `a3rig validate`.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>

#include "rigs/run/rig_runner.hpp"
#include "rigs/scenario/scenario.hpp"
#include "tests/agent_llm/scripted_server.hpp"
#include "tests/rigs/rig_test_support.hpp"

// After Eigen (through the rig's headers): httplib.h's includes clash with Eigen's when first.
#include <httplib.h>

namespace a3 {
namespace {


void clear_llm_environment() {
  for (const char* name : {"A3_LLM_API_KEY", "A3_LLM_API_KEY_FILE", "OPENAI_API_KEY", "A3_LLM_PROVIDER",
                           "A3_LLM_BASE_URL", "A3_LLM_MODEL"}) {
    ::unsetenv(name);
  }
}

using test::ScriptedServer;

// A model that only ever answers with text, whatever it is asked.
struct TextOnlyServer {
  httplib::Server server;
  std::thread thread;
  int port = 0;
  int requests_with_tools = 0;
  TextOnlyServer() {
    server.Post("/v1/chat/completions", [this](const httplib::Request& req, httplib::Response& res) {
      const nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
      if (body.is_object() && body.contains("tools")) ++requests_with_tools;
      const nlohmann::json answer = {
          {"id", "t"}, {"object", "chat.completion"}, {"model", "text-only"},
          {"choices", {{{"index", 0}, {"message", {{"role", "assistant"}, {"content", "I will take off now."}}},
                        {"finish_reason", "stop"}}}},
          {"usage", {{"prompt_tokens", 10}, {"completion_tokens", 6}, {"total_tokens", 16}}}};
      res.set_content(answer.dump(), "application/json");
    });
    port = server.bind_to_any_port("127.0.0.1");
    thread = std::thread([this] { server.listen_after_bind(); });
    while (!server.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ~TextOnlyServer() {
    server.stop();
    thread.join();
  }
  std::string base_url() const { return "http://127.0.0.1:" + std::to_string(port) + "/v1"; }
};

rigs::RunOptions llm_run(const std::string& scenario, const std::string& tools, const std::string& base_url) {
  rigs::RunOptions o = test::virtual_run(scenario, "llm-" + tools + "-" + scenario);
  o.agent = "llm";
  o.llm_tools = tools;
  o.llm_base_url = base_url;
  o.llm_model = "scripted-policy";
  o.llm_retries = 0;
  return o;
}

void expect_every_scenario_flown(const std::string& tools) {
  clear_llm_environment();
  ScriptedServer s;
  for (const std::string& scenario : rigs::builtin_scenario_names()) {
    SCOPED_TRACE(scenario + ", --llm-tools " + tools);
    const rigs::RunResult r = test::run(llm_run(scenario, tools, s.server.base_url()));
    EXPECT_EQ(r.status, "completed");
    EXPECT_EQ(rigs::run_exit_status(r.status), 0);
    EXPECT_TRUE(r.episode.value("success", false));
    const test::Scored score = test::score(r.episode);
    ASSERT_TRUE(score.valid) << score.problems;
    EXPECT_GE(score.pillars.alpha3, 0.9);
    for (const auto& rig : r.episode["_rig"]["turns"]) {
      if (rig["speaker"] != "agent") continue;
      SCOPED_TRACE("turn " + rig["turn"].dump());
      ASSERT_TRUE(rig.contains("attempt_log"));
      EXPECT_EQ(rig["attempts"], 1) << rig["attempt_log"].dump();
      EXPECT_EQ(rig["attempt_log"][0]["tool_mode"], tools);
    }
  }
}

TEST(LlmNativeClosedLoop, EveryBuiltInScenarioIsFlownWithNativeToolCalling) { expect_every_scenario_flown("native"); }

TEST(LlmNativeClosedLoop, EveryBuiltInScenarioIsFlownWithJsonInText) { expect_every_scenario_flown("json"); }

TEST(LlmNativeClosedLoop, AServerThatOnlyAnswersTextFailsNativeModeTurnByTurnAndTheRunEndsAgentFailed) {
  clear_llm_environment();
  TextOnlyServer text;
  rigs::RunOptions o = llm_run("survey-field", "native", text.base_url());
  const rigs::RunResult r = test::run(o);
  EXPECT_EQ(r.status.rfind("agent_failed: no agent turn had a valid action", 0), 0u) << r.status;
  EXPECT_EQ(rigs::run_exit_status(r.status), 6);
  EXPECT_EQ(r.episode["_rig"]["status"], r.status);
  EXPECT_GT(text.requests_with_tools, 0);
  int agent_turns = 0;
  for (const auto& t : r.episode["dialogue"]) {
    if (t["speaker"] != "agent") continue;
    ++agent_turns;
    EXPECT_TRUE(t["actions"].empty());
    EXPECT_EQ(t["intent"], "agent_error");
  }
  EXPECT_GE(agent_turns, 4);
  for (const auto& rig : r.episode["_rig"]["turns"]) {  // the turn's error, in words
    if (rig["speaker"] != "agent") continue;
    EXPECT_NE(rig.value("text", "").find("no usable reply after 3 attempts: the reply called no function (it "
                                         "answered with text only: \"I will take off now.\")"),
              std::string::npos)
        << rig.value("text", "");
  }
  const test::Scored score = test::score(r.episode);
  EXPECT_TRUE(score.valid) << score.problems;
}

TEST(LlmNativeClosedLoop, AnEndpointThatIsGoneEndsTheRunEndpointFailedAfterTwoAgentTurns) {
  clear_llm_environment();
  rigs::RunOptions o = llm_run("survey-field", "native", "http://127.0.0.1:9/v1");
  o.llm_connect_timeout_s = 2.0;
  const rigs::RunResult r = test::run(o);
  EXPECT_EQ(r.status.rfind("endpoint_failed: 2 agent turns in a row failed at the endpoint; last: POST "
                           "http://127.0.0.1:9/v1/chat/completions",
                           0),
            0u)
      << r.status;
  EXPECT_EQ(rigs::run_exit_status(r.status), 7);
  int agent_turns = 0;
  for (const auto& t : r.episode["dialogue"]) agent_turns += t["speaker"] == "agent" ? 1 : 0;
  EXPECT_EQ(agent_turns, 2);
  // Written with its status; too short a dialogue to be scored (as an interrupted run's).
  EXPECT_TRUE(std::filesystem::exists(r.episode_path));
  EXPECT_EQ(r.episode["_rig"]["status"], r.status);
}

TEST(LlmNativeClosedLoop, AStreamedNativeRunRecordsTheTimeToFirstAndLastTokenOfEveryTurn) {
  clear_llm_environment();
  ScriptedServer s;
  rigs::RunOptions o = llm_run("survey-field", "native", s.server.base_url());
  o.llm_stream = true;
  const rigs::RunResult r = test::run(o);
  ASSERT_EQ(r.status, "completed");
  EXPECT_TRUE(r.episode.value("success", false));
  int streamed = 0;
  for (const auto& rig : r.episode["_rig"]["turns"]) {
    if (rig["speaker"] != "agent") continue;
    SCOPED_TRACE("turn " + rig["turn"].dump());
    const auto& a = rig["attempt_log"].at(0);
    EXPECT_EQ(a.value("streamed", false), true) << a.dump();
    ASSERT_TRUE(a.contains("ttft_s") && a.contains("ttlt_s")) << a.dump();
    EXPECT_GT(a["ttft_s"].get<double>(), 0.0);
    EXPECT_LE(a["ttft_s"].get<double>(), a["ttlt_s"].get<double>());
    EXPECT_LE(a["ttlt_s"].get<double>(), a["wall_time_s"].get<double>());
    ++streamed;
  }
  EXPECT_GE(streamed, 4);
}

// The program, as a user runs it: native by default, the episode valid for `a3rig validate`.
TEST(LlmNativeClosedLoop, TheCommandFliesNativeByDefaultAndWritesAValidEpisode) {
  clear_llm_environment();
  ScriptedServer s;
  const std::string a3rig = std::string(A3_BINARY_DIR) + "/a3rig";
  const std::string out = std::string(::testing::TempDir()) + "a3rig-native-cli-" + std::to_string(::getpid());
  const std::string run = a3rig + " run --agent llm --llm-base-url " + s.server.base_url() +
                          " --llm-model scripted-policy --runtime virtual --scenario parcel-delivery --no-plot "
                          "--no-lcm-log -q --out " + out + " > " + out + ".log 2>&1";
  const int run_status = std::system(run.c_str());
  ASSERT_TRUE(WIFEXITED(run_status));
  ASSERT_EQ(WEXITSTATUS(run_status), 0) << run;
  const std::string validate = a3rig + " validate " + out + "/episode.json > /dev/null 2>&1";
  const int validate_status = std::system(validate.c_str());
  EXPECT_TRUE(WIFEXITED(validate_status) && WEXITSTATUS(validate_status) == 0) << validate;
  const nlohmann::json episode = nlohmann::json::parse(std::ifstream(out + "/episode.json"));
  EXPECT_EQ(episode["_rig"]["status"], "completed");
  for (const auto& rig : episode["_rig"]["turns"]) {
    if (rig["speaker"] != "agent") continue;
    EXPECT_EQ(rig["attempt_log"].at(0)["tool_mode"], "native");
  }
}

}  // namespace
}  // namespace a3
