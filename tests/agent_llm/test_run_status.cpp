// No silent success, from the recorded turns alone: two agent turns in a row that failed at the
// endpoint make endpoint_failed, a run whose agent turns carried no action is agent_failed, and
// their exit statuses (6, 7) beside the others; a sweep does not take such a run's cell as
// finished; the endpoint check before take-off passes any answer but the endpoint's failures;
// `a3rig run --agent llm` against an endpoint nobody listens on stops before take-off, non-zero
// within 20 s, naming the endpoint.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>

#include "rigs/run/agent_outcome.hpp"
#include "rigs/run/llm_run.hpp"
#include "rigs/run/rig_runner.hpp"
#include "rigs/sweep/cell_result.hpp"
#include "tests/agent_llm_client/scripted_openai_server.hpp"

namespace a3 {
namespace {

using nlohmann::json;

json agent_turn(int n, bool with_action, bool endpoint_failure) {
  json t = {{"turn", n}, {"speaker", "agent"}, {"intent", with_action ? "status_report" : "agent_error"},
            {"text", with_action ? "ok" : "agent error: no usable reply"}, {"actions", json::array()}};
  if (with_action) t["actions"].push_back({{"type", "mcp"}, {"name", "read_telemetry"}, {"args", json::object()}});
  json entry = {{"attempt", 3}, {"outcome", with_action ? "ok" : "call_failed"}};
  if (!with_action) {
    entry["endpoint_failure"] = endpoint_failure;
    entry["problems"] = {"POST http://x/v1/chat/completions: connection failed (turn " + std::to_string(n) + ")"};
  }
  t["_rig"] = {{"attempt_log", json::array({entry})}};
  return t;
}

json user_turn(int n) { return {{"turn", n}, {"speaker", "user"}, {"intent", "acknowledge"}, {"actions", json::array()}}; }

TEST(RunStatus, TwoAgentTurnsInARowFailedAtTheEndpointAreEndpointFailed) {
  std::vector<json> turns = {agent_turn(1, false, true), user_turn(2)};
  EXPECT_EQ(rigs::endpoint_failure_status(turns), "") << "one turn is not enough";
  turns.push_back(agent_turn(3, false, true));
  const std::string s = rigs::endpoint_failure_status(turns);
  EXPECT_EQ(s, "endpoint_failed: 2 agent turns in a row failed at the endpoint; last: POST "
               "http://x/v1/chat/completions: connection failed (turn 3)");
  EXPECT_EQ(rigs::run_exit_status(s), 7);
}

TEST(RunStatus, AGoodTurnOrAFailureThatIsNotTheEndpointsBreaksTheRow) {
  EXPECT_EQ(rigs::endpoint_failure_status({agent_turn(1, false, true), user_turn(2), agent_turn(3, true, false),
                                           user_turn(4), agent_turn(5, false, true)}),
            "");
  EXPECT_EQ(rigs::endpoint_failure_status({agent_turn(1, false, true), user_turn(2), agent_turn(3, false, false)}), "");
}

TEST(RunStatus, NoAgentTurnWithAnActionIsAgentFailed) {
  const std::vector<json> failed = {agent_turn(1, false, false), user_turn(2), agent_turn(3, false, false)};
  const std::string s = rigs::agent_failure_status(failed);
  EXPECT_EQ(s.rfind("agent_failed: no agent turn had a valid action (2 agent turns; last: POST", 0), 0u) << s;
  EXPECT_EQ(rigs::run_exit_status(s), 6);
  EXPECT_EQ(rigs::agent_failure_status({agent_turn(1, false, false), user_turn(2), agent_turn(3, true, false)}), "");
  EXPECT_EQ(rigs::agent_failure_status({}).rfind("agent_failed", 0), 0u) << "an agent that never spoke never acted";
}

TEST(RunStatus, ExitStatusesOfEveryStatus) {
  EXPECT_EQ(rigs::run_exit_status("completed"), 0);
  EXPECT_EQ(rigs::run_exit_status("time_limit"), 0);
  EXPECT_EQ(rigs::run_exit_status("interrupted"), 3);
  EXPECT_EQ(rigs::run_exit_status("node_failed: x"), 4);
  EXPECT_EQ(rigs::run_exit_status("realtime_violated: x"), 5);
  EXPECT_EQ(rigs::run_exit_status("agent_failed: x"), 6);
  EXPECT_EQ(rigs::run_exit_status("endpoint_failed: x"), 7);
  EXPECT_EQ(rigs::run_exit_status("output_failed: x"), 8);
  EXPECT_EQ(rigs::run_exit_status("never_flew: x"), 9);
}

TEST(RunStatus, AVehicleThatNeverLeftTheGroundOnAMissionIsNeverFlew) {
  EXPECT_EQ(rigs::never_flew_status(false, 0.004, 2),
            "never_flew: the vehicle never left the ground (highest 0.00 m) though the mission has 2 objectives");
  EXPECT_EQ(rigs::never_flew_status(true, 40.0, 2), "");
  EXPECT_EQ(rigs::never_flew_status(false, 0.0, 0), "") << "a mission without objectives needs no flight";
}

// A sweep cell whose run ended agent_failed or endpoint_failed is not a finished cell.
TEST(RunStatus, ASweepCountsAgentAndEndpointFailuresAsUnfinishedCells) {
  rigs::sweep::SweepCell cell;
  cell.scenario = "survey-field";
  cell.agent = "llm";
  cell.think_time = "0";
  cell.seed = 42;
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("a3rig-sweep-status-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const std::string status : {"agent_failed: no agent turn had a valid action (6 agent turns)",
                                   "endpoint_failed: 2 agent turns in a row failed at the endpoint; last: x",
                                   "completed", "never_flew: the vehicle never left the ground (highest 0.00 m)"}) {
    const json episode = {{"dialogue", json::array()},
                          {"_rig", {{"status", status}, {"agent", "llm"}, {"think_time", "0"}, {"seed", 42u}}}};
    std::ofstream(dir / "episode.json") << episode.dump();
    const rigs::sweep::CellCheck check = rigs::sweep::check_cell(dir, cell);
    if (status == "completed" || status.rfind("never_flew", 0) == 0) {  // never_flew: a flown cell that failed
      EXPECT_TRUE(check.complete) << check.why_not;
    } else {
      EXPECT_FALSE(check.complete) << status;
      EXPECT_EQ(check.why_not, "the run ended " + status);
    }
  }
}

agent::llm::LlmEndpoint endpoint_at(const std::string& base_url) {
  agent::llm::LlmEndpoint e;
  e.base_url = base_url;
  e.model = "probe-model";
  e.max_retries = 0;
  return e;
}

TEST(EndpointCheck, AnyAnswerButTheEndpointsFailuresPasses) {
  test::ScriptedOpenAiServer refuses(test::ScriptedOpenAiServer::sequence({{400, R"({"error":{"message":"no"}})"}}));
  EXPECT_NO_THROW(rigs::check_llm_endpoint(endpoint_at(refuses.base_url())));
  const json sent = refuses.requests().at(0).body;
  EXPECT_EQ(sent["max_tokens"], 16);
  EXPECT_FALSE(sent.contains("tools"));
  EXPECT_FALSE(sent.contains("response_format"));
}

TEST(EndpointCheck, AMissingModelOrAServerErrorStopsTheRunNamingTheEndpoint) {
  test::ScriptedOpenAiServer missing(
      test::ScriptedOpenAiServer::sequence({{404, R"({"error":{"message":"model probe-model not found"}})"}}));
  try {
    rigs::check_llm_endpoint(endpoint_at(missing.base_url()));
    FAIL() << "a 404 passed the check";
  } catch (const rigs::EndpointUnreachable& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the LLM endpoint " + missing.base_url() + " (model probe-model) does not answer"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("model probe-model not found"), std::string::npos) << what;
  }
  test::ScriptedOpenAiServer broken(test::ScriptedOpenAiServer::sequence({{503, "{}"}}));
  agent::llm::LlmEndpoint e = endpoint_at(broken.base_url());
  e.max_retries = 3;
  EXPECT_THROW(rigs::check_llm_endpoint(e), rigs::EndpointUnreachable);
  EXPECT_EQ(broken.requests().size(), 2u) << "the check retries once, whatever the run's retries";
}

TEST(RunCommand, AnUnreachableEndpointStopsBeforeTakeOffWithin20SecondsNamingIt) {
  const std::string out = std::string(::testing::TempDir()) + "a3rig-unreachable-" + std::to_string(::getpid());
  const std::string command = std::string(A3_BINARY_DIR) +
                              "/a3rig run --agent llm --llm-base-url http://127.0.0.1:9/v1 --llm-model x "
                              "--runtime virtual --out " + out + " 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  const int status = ::pclose(pipe);
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("a3rig run against http://127.0.0.1:9/v1 ended after %.2f s\n", elapsed_s);
  EXPECT_LT(elapsed_s, 20.0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7) << output;
  EXPECT_NE(output.find("the LLM endpoint http://127.0.0.1:9/v1 (model x) does not answer"), std::string::npos)
      << output;
  EXPECT_NE(output.find("status endpoint_failed"), std::string::npos) << output;
}

}  // namespace
}  // namespace a3
