// A stop (Ctrl-C) ends an LLM call that hangs: the client's transfer within 0.1 s, a backoff wait
// at once, and the llm agent's turn as interrupted with its attempt log; an endpoint that accepts
// TCP and then says nothing, or refuses it, fails the check before take-off within 25 s.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "agent/llm/llm_agent.hpp"
#include "agent/llm/llm_client.hpp"
#include "rigs/run/llm_run.hpp"
#include "tests/agent_llm/silent_endpoint.hpp"

namespace a3 {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

agent::llm::LlmEndpoint endpoint_at(const std::string& base_url) {
  agent::llm::LlmEndpoint e;
  e.base_url = base_url;
  e.model = "m";
  e.total_timeout_s = 30.0;
  e.max_retries = 2;
  e.backoff_initial_s = 20.0;
  return e;
}

// Calls abort_calls() on `client` after `after_s`, on a thread of its own.
std::thread abort_after(agent::llm::LlmClient& client, double after_s) {
  return std::thread([&client, after_s] {
    std::this_thread::sleep_for(std::chrono::duration<double>(after_s));
    client.abort_calls();
  });
}

TEST(LlmFaults, AStopEndsACallToASilentEndpointWithinATenthOfASecond) {
  test::SilentEndpoint silent;
  agent::llm::LlmClient client(endpoint_at(silent.base_url()));
  const auto t0 = Clock::now();
  std::thread stopper = abort_after(client, 0.3);
  const agent::llm::LlmCallResult r = client.chat({{"user", "hello"}});
  const double elapsed_s = seconds_since(t0);
  stopper.join();
  EXPECT_LT(elapsed_s, 0.3 + 0.1 + 0.2) << "the call went on " << elapsed_s - 0.3 << " s after the stop";
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.interrupted);
  ASSERT_EQ(r.attempts.size(), 1u) << "a stop is not retried";
  EXPECT_NE(r.error.find("interrupted: the run was stopped"), std::string::npos) << r.error;
  EXPECT_FALSE(agent::llm::is_endpoint_failure(r)) << "the endpoint is not at fault";
  const auto t1 = Clock::now();
  EXPECT_TRUE(client.chat({{"user", "again"}}).interrupted) << "the stop is sticky";
  EXPECT_LT(seconds_since(t1), 0.05);
}

TEST(LlmFaults, AStopWakesTheBackoffWaitBetweenRetries) {
  agent::llm::LlmClient client(endpoint_at("http://127.0.0.1:9/v1"));  // refused: retried after 20 s
  const auto t0 = Clock::now();
  std::thread stopper = abort_after(client, 0.3);
  const agent::llm::LlmCallResult r = client.chat({{"user", "hello"}});
  const double elapsed_s = seconds_since(t0);
  stopper.join();
  EXPECT_LT(elapsed_s, 0.6);
  EXPECT_TRUE(r.interrupted);
  EXPECT_NE(r.error.find("interrupted: the run was stopped while waiting to retry"), std::string::npos) << r.error;
}

TEST(LlmFaults, AStoppedTurnIsInterruptedWithItsAttemptLog) {
  test::SilentEndpoint silent;
  agent::llm::LlmAgent agent(std::make_unique<agent::llm::LlmClient>(endpoint_at(silent.base_url())));
  agent::AgentContext context;
  const agent::Mission mission;
  const std::vector<agent::Turn> dialogue;
  context.mission = &mission;
  context.dialogue = &dialogue;
  context.tools = &agent::ToolCatalog::builtin();
  std::thread stopper([&agent] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    agent.stop_deciding();
  });
  const auto t0 = Clock::now();
  const agent::AgentDecision d = agent.decide(context);
  const double elapsed_s = seconds_since(t0);
  stopper.join();
  EXPECT_LT(elapsed_s, 0.6);
  EXPECT_EQ(d.error.rfind("interrupted: the run was stopped during attempt 1 of the turn", 0), 0u) << d.error;
  EXPECT_EQ(d.attempts, 1) << "no stricter retry after a stop";
  ASSERT_EQ(d.attempt_log.size(), 1u);
  EXPECT_EQ(d.attempt_log[0].value("outcome", ""), "interrupted");
  EXPECT_FALSE(d.attempt_log[0].value("endpoint_failure", true));
  EXPECT_TRUE(d.actions.empty());
}

// The check before take-off against an endpoint that takes the connection and never answers,
// with the run's default 180 s per attempt: it gives up on its own, shorter timeout.
TEST(LlmFaults, ASilentEndpointFailsTheCheckBeforeTakeOffWithin25Seconds) {
  test::SilentEndpoint silent;
  agent::llm::LlmEndpoint e = endpoint_at(silent.base_url());
  e.total_timeout_s = 180.0;
  e.max_retries = 4;
  const auto t0 = Clock::now();
  try {
    rigs::check_llm_endpoint(e);
    ADD_FAILURE() << "a silent endpoint passed the check";
  } catch (const rigs::EndpointUnreachable& error) {
    EXPECT_NE(std::string(error.what()).find("does not answer"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("timed out"), std::string::npos) << error.what();
  }
  const double elapsed_s = seconds_since(t0);
  std::printf("the check gave up on a silent endpoint after %.1f s\n", elapsed_s);
  EXPECT_LT(elapsed_s, 25.0);
  EXPECT_EQ(silent.requests(), 2) << "one retry";
}

TEST(LlmFaults, ARefusingEndpointFailsTheCheckBeforeTakeOffWithin3Seconds) {
  agent::llm::LlmEndpoint e = endpoint_at("http://127.0.0.1:9/v1");
  e.total_timeout_s = 180.0;
  const auto t0 = Clock::now();
  EXPECT_THROW(rigs::check_llm_endpoint(e), rigs::EndpointUnreachable);
  EXPECT_LT(seconds_since(t0), 3.0);
}

}  // namespace
}  // namespace a3
