// Lockstep real time (DESIGN.md "Time"): on a loaded machine, every built-in mission flown in
// real time at --rtf 4 ends as its virtual-time run does (status, success, safety flags, turns,
// SP), with the vehicle's nodes in threads or in processes of their own, and no stale step; a
// frozen flight controller makes the lockstep vehicle wait (the wait is recorded), trips the
// motor failsafe when free-running, and is named when it stays frozen. Needs LCM UDP multicast
// on loopback (scripts/lcm-loopback.sh as root).
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <set>

#include "tests/integration/run_command.hpp"
#include "tests/rigs/real_time_support.hpp"

namespace a3::rigs {
namespace {

using a3::test::BusyLoops;
using a3::test::json;
using a3::test::Outcome;
using a3::test::outcome_of;
using a3::test::part_of_run;
using a3::test::read_json;
using a3::test::RunningRig;
namespace fs = std::filesystem;

struct Cell {
  std::string scenario;
  bool processes = false;
};

std::string cell_name(const ::testing::TestParamInfo<Cell>& info) {
  std::string name = info.param.scenario + (info.param.processes ? "_processes" : "_threads");
  for (char& c : name) c = c == '-' ? '_' : c;
  return name;
}

class LockstepUnderLoad : public ::testing::TestWithParam<Cell> {};

// The cells the default suite flies: the conflict both ways (two aircraft, the tightest timing),
// a delivery in processes (payload events across processes) and the thermal search in threads
// (sensor switching mid-flight). The eight others exercise the same lockstep on other missions
// and cost the suite about eleven of its 40 minutes on two cores: A3_SLOW_TESTS=1 flies them
// (and bench/rigs/realtime_matrix.py measures every scenario at several rtf and loads).
bool in_default_matrix(const Cell& cell) {
  if (cell.scenario == "traffic-conflict") return true;
  return cell.processes ? cell.scenario == "parcel-delivery" : cell.scenario == "thermal-search";
}

TEST_P(LockstepUnderLoad, EndsAsInVirtualTimeAtRtf4WithTwoBusyLoops) {
  A3_REQUIRE_MULTICAST();
  const Cell cell = GetParam();
  if (!in_default_matrix(cell) && std::getenv("A3_SLOW_TESTS") == nullptr) {
    GTEST_SKIP() << "a slow cell (100-170 s): the default suite flies four cells (traffic-conflict both ways, "
                    "parcel-delivery in processes, thermal-search in threads); A3_SLOW_TESTS=1 flies every "
                    "scenario both ways";
  }
  RunOptions v = a3::test::virtual_run(cell.scenario, "lockstep-" + cell_name({cell, 0}));
  RunOptions r = v;
  r.runtime = Runtime::kReal;
  r.real_time_factor = 4.0;
  r.processes = cell.processes;
  r.a3rig_exe = a3::test::a3rig();
  r.out_dir = v.out_dir.string() + "-real";
  const RunResult a = a3::test::run(v);
  RunResult b;
  {
    const BusyLoops load(2);
    b = a3::test::run(r);
  }
  const Outcome x = outcome_of(a.episode), y = outcome_of(b.episode);
  const json& rt = b.episode["_rig"]["realtime"];
  std::cout << cell.scenario << (cell.processes ? " (processes)" : " (threads)") << ": virtual " << x.status
            << ", lockstep rtf 4 under 2 busy loops " << y.status << "; achieved " << rt["rtf"]["achieved"]
            << ", worst window " << rt["rtf"]["worst_window"] << ", lockstep " << rt["lockstep"].dump() << "\n";
  EXPECT_EQ(x.status, "completed");
  a3::test::expect_same_outcome(x, y);
  EXPECT_EQ(rt["sync"], "lockstep");
  EXPECT_EQ(rt["stale_steps"].get<int>(), 0);
  EXPECT_GT(rt["lockstep"]["grants"].get<double>(), 0.0);
  // Every node's counters reached the episode through the bus, from this process or another.
  const json& counters = b.episode["_rig"]["counters"];
  for (const char* node : {"dynamics", "bridge", "fc", "linkemu", "tool_server", "conversation"}) {
    EXPECT_TRUE(counters.contains(node)) << node << " missing from " << counters.dump();
  }
  EXPECT_GT(counters["fc"]["clock_grants"].get<int>(), 0);
  EXPECT_GT(counters["dynamics"]["steps"].get<int>(), 0);
  fs::remove_all(v.out_dir);
  fs::remove_all(r.out_dir);
}

std::vector<Cell> every_builtin_both_ways() {
  std::vector<Cell> cells;
  for (const char* s : {"survey-field", "parcel-delivery", "bridge-inspection", "thermal-search", "nfz-detour",
                        "traffic-conflict"}) {
    cells.push_back({s, false});
    cells.push_back({s, true});
  }
  return cells;
}

INSTANTIATE_TEST_SUITE_P(BuiltInScenarios, LockstepUnderLoad, ::testing::ValuesIn(every_builtin_both_ways()), cell_name);

// Flies survey-field with --processes at --rtf 4 (the flight, not the freeze, is what takes
// time) and freezes the process of one part (SIGSTOP) for freeze_s of wall time once the vehicle
// is airborne; returns the episode and the exit status.
std::pair<json, int> run_with_frozen_part(const std::string& part, const std::string& sync, double freeze_s,
                                          const std::string& tag) {
  const a3::test::TempDir dir(tag);
  const fs::path out = dir.path() / "out";
  RunningRig rig({a3::test::a3rig(), "run", "--processes", "--sync", sync, "--scenario", "survey-field", "--rtf", "4",
                  "--no-plot", "--out", out.string()},
                 dir.path() / "output.txt");
  EXPECT_TRUE(rig.wait_for_output("turn  3", 120.0)) << rig.text();
  std::this_thread::sleep_for(std::chrono::seconds(3));  // climbing
  const pid_t frozen = part_of_run(rig.pid, part);
  EXPECT_GT(frozen, 0) << rig.text();
  ::kill(frozen, SIGSTOP);
  std::this_thread::sleep_for(std::chrono::duration<double>(freeze_s));
  ::kill(frozen, SIGCONT);
  const int status = rig.wait_exit(400.0);
  std::cout << rig.text().substr(rig.text().size() > 1500 ? rig.text().size() - 1500 : 0) << "\n";
  if (!fs::exists(out / "episode.json")) return {json(), status};
  return {read_json(out / "episode.json"), status};
}

std::pair<json, int> run_with_frozen_fc(const std::string& sync, double freeze_s, const std::string& tag) {
  return run_with_frozen_part("fc", sync, freeze_s, tag);
}

bool has_event(const json& e, const std::string& kind) {
  for (const auto& ev : e["_rig"]["safety_events"]) {
    if (ev.value("kind", "") == kind) return true;
  }
  return false;
}

// 1.5 s: shorter than the 3 s of silence that name a frozen node (statistics come every second).
TEST(LockstepFaults, AFrozenFlightControllerMakesTheLockstepVehicleWait) {
  A3_REQUIRE_MULTICAST();
  const auto [e, status] = run_with_frozen_fc("lockstep", 1.5, "lockstep-frozen-fc");
  ASSERT_TRUE(e.is_object());
  EXPECT_EQ(status, 0);
  EXPECT_EQ(e["_rig"]["status"], "completed");
  EXPECT_TRUE(e["success"].get<bool>());
  EXPECT_FALSE(e["_rig"]["trajectory"]["crashed"].get<bool>());
  const json& rt = e["_rig"]["realtime"];
  EXPECT_EQ(rt["stale_steps"].get<int>(), 0);
  EXPECT_FALSE(has_event(e, "command_timeout"));
  // The wait is recorded: simulated time stood still while the fc was frozen.
  EXPECT_GT(rt["lockstep"]["wait_max_s"].get<double>(), 1.0) << rt.dump();
  EXPECT_GT(rt["lockstep"]["wait_total_s"].get<double>(), 1.0) << rt.dump();
}

// The tool server and the airspace monitor (the vehicle part) frozen for 2 s of wall time, 8 s of
// simulated time at --rtf 4: they answer every grant, so simulated time waits for them and the
// mission goes as in virtual time, to the tenth of a second, instead of the route going on 8 s late.
TEST(LockstepFaults, AFrozenToolServerMakesSimulatedTimeWait) {
  A3_REQUIRE_MULTICAST();
  const RunOptions virtual_options = a3::test::virtual_run("survey-field", "lockstep-frozen-vehicle");
  const RunResult v = a3::test::run(virtual_options);
  const auto [e, status] = run_with_frozen_part("vehicle", "lockstep", 2.0, "lockstep-frozen-vehicle");
  ASSERT_TRUE(e.is_object());
  EXPECT_EQ(status, 0);
  a3::test::expect_same_outcome(outcome_of(v.episode), outcome_of(e));
  const json& done = e["_rig"]["objectives"]["objectives"];
  const json& done_virtual = v.episode["_rig"]["objectives"]["objectives"];
  ASSERT_EQ(done.size(), done_virtual.size());
  for (std::size_t i = 0; i < done.size(); ++i) {
    ASSERT_TRUE(done[i]["done_at_s"].is_number() && done_virtual[i]["done_at_s"].is_number())
        << done[i].dump() << " / virtual " << done_virtual[i].dump();
    EXPECT_NEAR(done[i]["done_at_s"].get<double>(), done_virtual[i]["done_at_s"].get<double>(), 0.1) << done[i].dump();
  }
  const json& waited = e["_rig"]["realtime"]["lockstep"]["wait_on_s"];
  EXPECT_GT(waited.value("tool_server", 0.0) + waited.value("airspace_monitor", 0.0), 1.5) << waited.dump();
  fs::remove_all(virtual_options.out_dir);
}

TEST(LockstepFaults, FreeRunningAFrozenFlightControllerTripsTheMotorFailsafe) {
  A3_REQUIRE_MULTICAST();
  const auto [e, status] = run_with_frozen_fc("free", 1.5, "free-frozen-fc");
  ASSERT_TRUE(e.is_object());
  const json& rt = e["_rig"]["realtime"];
  EXPECT_EQ(rt["sync"], "free");
  EXPECT_GT(rt["stale_steps"].get<int>(), 0) << rt.dump();
  EXPECT_TRUE(has_event(e, "command_timeout")) << e["_rig"]["safety_events"].dump();
  // The frozen controller missed its deadlines: the episode says the run was not what it claimed.
  EXPECT_GT(rt["nodes"]["fc"]["deadline_misses"].get<double>(), 0.0) << rt.dump();
  EXPECT_NE(status, 0);
}

TEST(LockstepFaults, AFlightControllerThatStaysFrozenIsNamed) {
  A3_REQUIRE_MULTICAST();
  const auto [e, status] = run_with_frozen_fc("lockstep", 5.0, "lockstep-stuck-fc");
  ASSERT_TRUE(e.is_object());
  EXPECT_EQ(status, 4);
  const std::string why = e["_rig"]["status"];
  EXPECT_EQ(why.rfind("node_failed: fc", 0), 0u) << why;
  EXPECT_NE(why.find("unresponsive"), std::string::npos) << why;
  EXPECT_FALSE(e["_rig"]["trajectory"]["crashed"].get<bool>());
}

}  // namespace
}  // namespace a3::rigs
