// What the rig must get right beyond a clean run: agent latency passes in the world (a slow
// agent misses a conflict and a breach is measured), the safety gate refuses unsafe actions
// before the flight controller sees them, a lost link triggers the flight controller's
// failsafe, replayed corpus turns run, and a seed fixes the whole episode.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "agent/conversation/replay_agent.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

using nlohmann::json;

bool flag(const json& e, const char* name) { return e["final_state"]["safety_flags"][name].get<bool>(); }

int count_events(const json& e, const std::string& kind) {
  int n = 0;
  for (const auto& ev : e["_rig"]["safety_events"]) {
    if (ev["kind"] == kind && ev["detail"].get<std::string>().rfind("enter", 0) == 0) ++n;
  }
  return n;
}

// A constant URLLC link as a trace, lossless until dead_from_s and dead (100 % loss) after.
json constant_link_trace(double dead_from_s) {
  json trace = json::array();
  for (int t = 0; t <= 600; t += 20) {
    const bool dead = t >= dead_from_s;
    trace.push_back({{"t_s", t}, {"slice", "URLLC"}, {"lat_ms", 7.0}, {"jitter_ms", 1.0},
                     {"loss_pct", dead ? 100.0 : 0.0}, {"throughput_mbps", 90.0}, {"edge_load", 0.3}});
  }
  return trace;
}

// A built-in scenario flown over that trace (written into dir).
std::string scenario_with_trace(const a3::test::TempDir& dir, const std::string& builtin, double dead_from_s) {
  std::ofstream(dir.path() / "trace.json") << constant_link_trace(dead_from_s).dump();
  std::ifstream base(std::string(A3_SOURCE_DIR) + "/rigs/scenarios/" + builtin + ".json");
  json scenario = json::parse(base);
  scenario["name"] = builtin + "-constant-link";
  scenario["network"] = {{"trace", "trace.json"}, {"trace_period_s", 20}};
  std::ofstream(dir.path() / "scenario.json") << scenario.dump();
  return (dir.path() / "scenario.json").string();
}

TEST(RigBehaviour, AThinkTimeThatMissesTheConflictCausesAMeasuredBreach) {
  RunOptions fast = a3::test::virtual_run("traffic-conflict", "fast");
  RunOptions slow = fast;
  // 90 s per decision: the vehicle reaches the tower late and hovers there while the patrol
  // passes (at t ≈ 287 s and 353 s), with no turn in time to ask it to yield.
  slow.think_time = "90";
  slow.out_dir += "-slow";
  const RunResult a = a3::test::run(fast);
  const RunResult b = a3::test::run(slow);
  EXPECT_FALSE(flag(a.episode, "separation_breach"));
  EXPECT_EQ(count_events(a.episode, "separation_breach"), 0);
  EXPECT_TRUE(flag(b.episode, "separation_breach"));
  EXPECT_GE(count_events(b.episode, "separation_breach"), 1);
  const auto sa = a3::test::score(a.episode), sb = a3::test::score(b.episode);
  ASSERT_TRUE(sa.valid && sb.valid) << sa.problems << sb.problems;
  EXPECT_DOUBLE_EQ(sa.pillars.sp, 1.0);
  EXPECT_LT(sb.pillars.sp, 1.0);
  // The think time really was charged: each agent turn's decision came 90 s after its start.
  for (const auto& t : b.episode["_rig"]["turns"]) {
    if (t["speaker"] == "agent") {
      EXPECT_NEAR(t["decided_s"].get<double>() - t["started_s"].get<double>(), 90.0, 1e-6);
    }
  }
  std::filesystem::remove_all(fast.out_dir);
  std::filesystem::remove_all(slow.out_dir);
}

TEST(RigBehaviour, TheSameSeedGivesTheSameEpisode) {
  RunOptions o = a3::test::virtual_run("bridge-inspection", "seed");
  o.seed = 7;
  const RunResult a = a3::test::run(o);
  const RunResult b = a3::test::run(o);
  RunOptions other = o;
  other.seed = 8;
  const RunResult c = a3::test::run(other);
  EXPECT_EQ(a.episode["dialogue"], b.episode["dialogue"]);
  EXPECT_EQ(a.episode["final_state"], b.episode["final_state"]);
  EXPECT_EQ(a.episode["_rig"]["trajectory"], b.episode["_rig"]["trajectory"]);
  EXPECT_EQ(a.episode["_rig"]["link"], b.episode["_rig"]["link"]);
  EXPECT_NE(a.episode["dialogue"], c.episode["dialogue"]);  // other network samples, at least
  std::filesystem::remove_all(o.out_dir);
}

// A recorded agent that asks for unsafe things: the gate refuses each with a reason, and none
// of them becomes a flight-controller command.
TEST(RigBehaviour, TheSafetyGateRefusesUnsafeActions) {
  const a3::test::TempDir dir("gate");
  json episode = {{"_meta", {{"gen_time_s", 4.0}}}, {"dialogue", json::array()}};
  auto agent_turn = [&](int n, const std::string& intent, json actions) {
    episode["dialogue"].push_back({{"turn", n}, {"speaker", "agent"}, {"intent", intent}, {"actions", actions}});
  };
  auto mcp = [](const std::string& name, json args) { return json{{"type", "mcp"}, {"name", name}, {"args", args}}; };
  agent_turn(1, "launch", {mcp("takeoff", {{"altitude_m", 40}})});
  agent_turn(3, "unsafe", {mcp("set_waypoint", {{"x", 5000}, {"y", 100}, {"z", 40}}),
                           mcp("set_waypoint", {{"x", 200}, {"y", 100}, {"z", 400}}),
                           mcp("set_altitude", {{"z", -20}}), mcp("fly_to_moon", json::object())});
  agent_turn(5, "land", {mcp("land", json::object())});
  std::ofstream(dir.path() / "recorded.json") << episode.dump();
  // A lossless link, so that every refusal comes back as an observation (a lost action
  // would come back as a timeout).
  RunOptions o = a3::test::virtual_run(scenario_with_trace(dir, "survey-field", 1e9), "gate");
  o.agent = "replay:" + (dir.path() / "recorded.json").string();
  const RunResult r = a3::test::run(o);
  const json& turn = r.episode["dialogue"][2];
  ASSERT_EQ(turn["intent"], "unsafe");
  ASSERT_EQ(turn["obs"].size(), 4u);
  EXPECT_EQ(turn["obs"][0]["result"]["status"], "refused");
  EXPECT_NE(turn["obs"][0]["result"].dump().find("geofence"), std::string::npos) << turn["obs"][0].dump();
  EXPECT_EQ(turn["obs"][1]["result"]["status"], "refused");
  EXPECT_EQ(turn["obs"][2]["result"]["status"], "error");  // z below the schema's minimum
  EXPECT_EQ(turn["obs"][3]["result"]["status"], "error") << r.episode["_rig"]["counters"].dump();  // unknown tool
  EXPECT_NE(turn["obs"][3]["result"].dump().find("fly_to_moon"), std::string::npos);
  // Only the take-off and the landing reached the flight controller.
  EXPECT_EQ(r.episode["_rig"]["counters"]["tool_server"]["fc_commands"].get<int>(), 2);
  EXPECT_GE(r.episode["_rig"]["counters"]["tool_server"]["gate_refusals"].get<int>(), 2);
  EXPECT_LT(r.episode["_rig"]["trajectory"]["max_altitude_m"].get<double>(), 45.0);
  std::filesystem::remove_all(o.out_dir);
}

// A recorded agent that only reads telemetry: the vehicle never leaves the ground, and a run
// with objectives that flew nothing ends never_flew (exit 9), not completed.
TEST(RigBehaviour, AnAgentThatNeverTakesOffEndsNeverFlew) {
  const a3::test::TempDir dir("grounded");
  json episode = {{"_meta", {{"gen_time_s", 2.0}}}, {"dialogue", json::array()}};
  for (int n : {1, 3, 5, 7}) {
    episode["dialogue"].push_back({{"turn", n}, {"speaker", "agent"}, {"intent", "status_report"},
                                   {"actions", {{{"type", "mcp"}, {"name", "read_telemetry"}, {"args", json::object()}}}}});
  }
  std::ofstream(dir.path() / "recorded.json") << episode.dump();
  RunOptions o = a3::test::virtual_run("survey-field", "grounded");
  o.agent = "replay:" + (dir.path() / "recorded.json").string();
  const RunResult r = a3::test::run(o);
  EXPECT_EQ(r.status.rfind("never_flew: the vehicle never left the ground", 0), 0u) << r.status;
  EXPECT_EQ(rigs::run_exit_status(r.status), 9);
  EXPECT_EQ(r.episode["_rig"]["status"], r.status);
  EXPECT_FALSE(r.episode["success"].get<bool>());
  std::filesystem::remove_all(o.out_dir);
}

// The link dies mid-flight (a trace with total loss from t = 40 s): the ground's heartbeats
// stop reaching the vehicle, the flight controller holds, then returns home and lands.
TEST(RigBehaviour, ALostLinkTriggersTheFlightControllersFailsafe) {
  const a3::test::TempDir dir("linkloss");
  RunOptions o = a3::test::virtual_run(scenario_with_trace(dir, "survey-field", 40.0), "linkloss");
  const RunResult r = a3::test::run(o);
  const auto& fc = r.episode["_rig"]["flight_controller"];
  ASSERT_FALSE(fc["failsafes"].empty()) << fc.dump();
  EXPECT_EQ(fc["failsafes"][0], "link_loss");
  const auto modes = fc["modes"].get<std::vector<std::string>>();
  const auto hold = std::find(modes.begin(), modes.end(), "hold");
  EXPECT_NE(std::find(hold, modes.end(), "return_home"), modes.end()) << fc.dump();
  EXPECT_EQ(modes.back(), "disarmed");
  EXPECT_NEAR(r.episode["final_state"]["uav"]["pose"]["z"].get<double>(), 0.0, 0.05);
  EXPECT_GT(r.episode["_rig"]["link"]["up"]["lost"].get<int>(), 10);
  EXPECT_GT(r.episode["_rig"]["counters"]["conversation"]["timeouts"].get<int>(), 0);
  std::filesystem::remove_all(o.out_dir);
}

TEST(RigBehaviour, APublicCorpusEpisodeReplaysOnItsOwnInitialState) {
  const auto file = a3::test::shared_dir() / "alphabench/eval_runs/openai/chatgpt-4o-latest/uav/sc-0000-ep-00.json";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << a3::test::shared_missing_message(file);
  RunOptions o = a3::test::virtual_run("alphabench:openai/chatgpt-4o-latest/uav/sc-0000-ep-00.json", "replay");
  o.agent = "replay:alphabench:openai/chatgpt-4o-latest/uav/sc-0000-ep-00.json";
  const RunResult r = a3::test::run(o);
  const json& e = r.episode;
  ASSERT_GE(e["dialogue"].size(), 8u);
  // The recorded agent turns were played in order with the recorded timing (10.8 s / 5).
  const agent::ReplayAgent recorded = agent::ReplayAgent::from_file(file);
  EXPECT_EQ(e["dialogue"][0]["intent"], "initiate_mission");
  EXPECT_NEAR(e["_rig"]["turns"][0]["think_time_s"].get<double>(), recorded.latency_per_turn_s(), 1e-9);
  EXPECT_EQ(e["initial_state"]["env"], json::parse(std::ifstream(file))["initial_state"]["env"]);
  EXPECT_TRUE(a3::test::score(e).valid) << a3::test::score(e).problems;
  std::filesystem::remove_all(o.out_dir);
}

// Runs where a supervisor's turn came while a leg was being flown (a degraded link on eMBB),
// or where the way home skirts a no-fly zone: the scripted agent must not take such a turn as
// "the leg is done" (it once captured 400 m short of the tower, went home before surveying,
// and landed 200 m from home on its own detour back).
TEST(RigBehaviour, TheScriptedAgentFinishesEachLegBeforeTheNext) {
  struct Case {
    std::string scenario, slice;
    uint64_t seed;
  };
  for (const Case& k : std::vector<Case>{{"traffic-conflict", "eMBB", 1},
                                         {"traffic-conflict", "eMBB", 2},
                                         {"survey-field", "eMBB", 1},
                                         {"nfz-detour", "URLLC", 2}}) {
    const std::string what = k.scenario + " on " + k.slice + ", seed " + std::to_string(k.seed);
    RunOptions o = a3::test::virtual_run(k.scenario, "legs-" + k.scenario + "-" + std::to_string(k.seed));
    o.slice = linkemu::parse_slice(k.slice);
    o.seed = k.seed;
    const RunResult r = a3::test::run(o);
    EXPECT_EQ(r.status, "completed") << what;
    EXPECT_TRUE(r.episode["success"].get<bool>()) << what << ": " << r.episode["_rig"]["objectives"].dump();
    if (k.scenario == "traffic-conflict") {
      int captures = 0;
      for (const auto& t : r.episode["dialogue"]) {
        for (const auto& ob : t["obs"]) {
          if (ob.value("tool", "") != "capture_image") continue;
          ++captures;
          const auto& pose = ob["result"]["pose"];
          EXPECT_NEAR(pose["x"].get<double>(), 500.0, 20.0) << what;  // the tower
          EXPECT_NEAR(pose["y"].get<double>(), 300.0, 20.0) << what;
        }
      }
      EXPECT_EQ(captures, 1) << what;
    }
    std::filesystem::remove_all(o.out_dir);
  }
}

}  // namespace
}  // namespace a3::rigs
