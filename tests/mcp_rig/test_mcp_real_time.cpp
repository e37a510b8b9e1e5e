// One short MCP session in real time: the client's own time between calls passes in the
// simulated world (the agent runs on the conversation's thread), and a client that leaves
// mid-dialogue ends the run with an interrupted episode. Label realtime: run it alone.
#include <gtest/gtest.h>

#include <thread>

#include "rigs/generator/scenario_spec.hpp"
#include "rigs/run/mcp_run.hpp"
#include "tests/rigs/real_time_support.hpp"

namespace a3::rigs {
namespace {

using nlohmann::json;

TEST(McpRealTime, TheClientsTimeBetweenCallsPassesInTheWorld) {
  A3_REQUIRE_MULTICAST();
  RunOptions o = test::virtual_run("parcel-delivery", "mcp-real-time");
  o.runtime = Runtime::kReal;
  o.lcm_url = test::private_udpm_url();
  const Scenario s = load_scenario_spec(o.scenario, o.shared_dir);
  std::atomic<bool> stop{false};
  auto agent = make_mcp_agent(s, o, &stop);
  agent::mcp::McpCallResult telemetry, reply;
  std::thread client([&] {
    telemetry = agent->call_tool("read_telemetry", json::object(), {});
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // the client thinks
    reply = agent->call_tool("report_turn", {{"intent", "preflight_check"}, {"text", "Ready."}}, {});
    agent->client_closed();
  });
  const auto wall0 = std::chrono::steady_clock::now();
  const RunResult r = run_mcp_episode(s, o, *agent, {}, &stop);
  client.join();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count(), 120.0);
  EXPECT_EQ(r.status, "interrupted");
  EXPECT_FALSE(telemetry.is_error) << telemetry.structured.dump();
  EXPECT_FALSE(reply.is_error) << reply.structured.dump();
  EXPECT_EQ(reply.structured.value("speaker", ""), "user") << reply.structured.dump();
  ASSERT_GE(r.episode["_rig"]["turns"].size(), 1u) << r.episode.dump();
  const json& turn1 = r.episode["_rig"]["turns"][0];
  EXPECT_EQ(turn1.value("steps", 0), 2);
  // At least the client's 1.5 s of thinking passed in the world during the turn (generous bounds).
  EXPECT_GE(turn1.value("think_time_s", 0.0), 1.2) << turn1.dump();
  EXPECT_LT(turn1.value("think_time_s", 0.0), 30.0) << turn1.dump();
}

}  // namespace
}  // namespace a3::rigs
