// Whole episodes flown by an MCP client of the live rig, in virtual time: a C++ client on a
// thread calls McpRig::call_tool as the MCP server would (no JSON-RPC) and flies
// parcel-delivery to success; bad calls answer is_error without a turn step; a call after the
// end names the status and the episode; a client that leaves mid-dialogue leaves an
// interrupted episode; the client's think time is charged to its turn.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <thread>

#include "rigs/generator/scenario_spec.hpp"
#include "rigs/run/mcp_run.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

using agent::mcp::McpAgent;
using agent::mcp::McpCallResult;
using nlohmann::json;

// The client's side: calls with a log of what came back.
struct Client {
  McpAgent& rig;
  std::vector<std::string> log;
  int progress_reports = 0;
  McpCallResult call(const std::string& name, const json& args) {
    McpCallResult r = rig.call_tool(name, args, [this](double, std::optional<double>, const std::string&) {
      ++progress_reports;
    });
    log.push_back(name + " -> " + (r.is_error ? "ERROR " : "") + r.structured.dump().substr(0, 200));
    return r;
  }
  std::string transcript() const {
    std::string out;
    for (const auto& l : log) out += l + "\n";
    return out;
  }
};

struct Flight {
  RunResult result;
  std::string transcript;
};

// Runs `scenario` with the client's `fly` on a thread; the run on this one.
template <typename Fly>
Flight fly_episode(const std::string& scenario, const std::string& tag, Fly fly, const std::string& think_time = "0") {
  RunOptions o = test::virtual_run(scenario, "mcp-" + tag);
  o.think_time = think_time;
  const Scenario s = load_scenario_spec(o.scenario, o.shared_dir);
  std::atomic<bool> stop{false};
  auto agent = make_mcp_agent(s, o, &stop);
  Client client{*agent, {}, 0};
  std::thread client_thread([&] { fly(client); });
  Flight f;
  f.result = run_mcp_episode(s, o, *agent, {}, &stop);
  client_thread.join();
  f.transcript = client.transcript();
  if (std::getenv("A3_MCP_TRANSCRIPT") != nullptr) std::fprintf(stderr, "%s", f.transcript.c_str());
  return f;
}

json turn_call(const std::string& intent, const std::string& text) { return {{"intent", intent}, {"text", text}}; }

// parcel-delivery: take off, fly to the drop point and descend over it, come home, land.
void fly_parcel_delivery(Client& c) {
  EXPECT_TRUE(c.call("no_such_tool", json::object()).is_error);
  EXPECT_TRUE(c.call("takeoff", {{"altitude_m", "high"}}).is_error);
  EXPECT_FALSE(c.call("read_telemetry", json::object()).is_error);
  EXPECT_FALSE(c.call("report_turn", turn_call("preflight_check", "Telemetry checked; ready to launch.")).is_error);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the client thinks: charged to turn 3
  EXPECT_FALSE(c.call("takeoff", {{"altitude_m", 50}}).is_error);
  EXPECT_FALSE(c.call("navigate_to", {{"waypoints", {{600, 400, 50}, {600, 400, 5}}}}).is_error);
  EXPECT_FALSE(c.call("report_turn", turn_call("deliver_package", "Flying the parcel to the drop point.")).is_error);
  EXPECT_FALSE(c.call("return_to_home", json::object()).is_error);
  EXPECT_FALSE(c.call("report_turn", turn_call("return_to_home", "Parcel delivered; returning home to land.")).is_error);
  json reply = json::object();
  for (int turn = 0; turn < 4 && !reply.value("dialogue_over", false); ++turn) {
    c.call("read_telemetry", json::object());
    reply = c.call("report_turn", turn_call("confirm_landing", "Landed at home.")).structured;
  }
  EXPECT_TRUE(reply.value("dialogue_over", false)) << reply.dump();
}

TEST(McpEpisode, AClientFliesParcelDeliveryToSuccessAndTheEpisodeIsValid) {
  const Flight f = fly_episode("parcel-delivery", "success", fly_parcel_delivery);
  EXPECT_EQ(f.result.status, "completed") << f.transcript;
  EXPECT_TRUE(f.result.episode.value("success", false)) << f.transcript;
  const test::Scored scored = test::score(f.result.episode);
  EXPECT_TRUE(scored.valid) << scored.problems;
  EXPECT_EQ(f.result.episode["_meta"].value("model", ""), "a3rig/mcp") << f.result.episode["_meta"].dump();
  const json& dialogue = f.result.episode["dialogue"];
  ASSERT_GE(dialogue.size(), 8u);
  // The bad calls made no step: turn 1 is read_telemetry alone, in two steps with report_turn.
  ASSERT_EQ(dialogue[0]["actions"].size(), 1u);
  EXPECT_EQ(dialogue[0]["actions"][0]["name"], "read_telemetry");
  EXPECT_EQ(dialogue[0]["intent"], "preflight_check");
  EXPECT_EQ(dialogue[2]["actions"].size(), 2u);
  const json& rig3 = f.result.episode["_rig"]["turns"][2];
  EXPECT_EQ(rig3.value("steps", 0), 3);
  EXPECT_GE(rig3.value("think_time_s", 0.0), 0.3) << rig3.dump();
}

TEST(McpEpisode, ACallAfterTheEndNamesTheStatusAndTheEpisode) {
  RunOptions o = test::virtual_run("parcel-delivery", "mcp-after");
  const Scenario s = load_scenario_spec(o.scenario, o.shared_dir);
  std::atomic<bool> stop{false};
  auto agent = make_mcp_agent(s, o, &stop);
  agent->set_episode_over("completed", o.out_dir / "episode.json");
  const McpCallResult r = agent->call_tool("read_telemetry", json::object(), {});
  EXPECT_TRUE(r.is_error);
  EXPECT_NE(r.text.find("completed"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find((o.out_dir / "episode.json").string()), std::string::npos) << r.text;
  EXPECT_TRUE(agent->episode_over());
}

TEST(McpEpisode, AClientThatLeavesMidDialogueLeavesAnInterruptedEpisode) {
  McpCallResult refused;
  McpCallResult after;
  McpAgent* rig = nullptr;
  const Flight f = fly_episode("parcel-delivery", "closed", [&](Client& c) {
    rig = &c.rig;
    c.call("read_telemetry", json::object());
    c.call("report_turn", turn_call("preflight_check", "Ready."));
    c.call("takeoff", {{"altitude_m", 50}});
    refused = c.call("navigate_to", {{"waypoints", {{5000, 5000, 50}}}});
    c.rig.client_closed();
    after = c.call("read_telemetry", json::object());
  });
  EXPECT_EQ(f.result.status, "interrupted") << f.transcript;
  EXPECT_TRUE(std::filesystem::exists(f.result.episode_path));
  EXPECT_TRUE(refused.is_error) << refused.structured.dump();
  EXPECT_EQ(refused.structured.value("status", ""), "refused") << refused.structured.dump();
  EXPECT_TRUE(after.is_error);
  // Once written, every call names the status.
  const McpCallResult late = rig->call_tool("read_telemetry", json::object(), {});
  EXPECT_TRUE(late.is_error);
  EXPECT_NE(late.text.find("interrupted"), std::string::npos) << late.text;
}

TEST(McpEpisode, AThinkTimeModelIsChargedInsteadOfTheClientsWallTime) {
  const Flight f = fly_episode(
      "parcel-delivery", "think",
      [](Client& c) {
        c.call("read_telemetry", json::object());
        std::this_thread::sleep_for(std::chrono::milliseconds(200));  // not charged: the model is
        c.call("report_turn", turn_call("preflight_check", "Ready."));
        c.rig.client_closed();
      },
      "fixed:2");
  EXPECT_EQ(f.result.status, "interrupted") << f.transcript;
  const json& rig1 = f.result.episode["_rig"]["turns"][0];
  EXPECT_EQ(rig1.value("steps", 0), 2);
  EXPECT_DOUBLE_EQ(rig1.value("think_time_s", 0.0), 4.0) << rig1.dump();  // 2 s for each of the 2 steps
}

}  // namespace
}  // namespace a3::rigs
