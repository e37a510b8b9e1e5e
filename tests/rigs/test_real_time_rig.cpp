// The rig in real time: the same mission gives the same outcome as in virtual time (the time
// rule: the world's clock, not the machine's speed, decides what happens), and `a3rig run` as a
// program: what it writes, its exit statuses, an interrupted run still written, and a node
// process that dies named in the result. Needs LCM UDP multicast on loopback
// (scripts/lcm-loopback.sh as root); skipped with that hint where it is missing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fcntl.h>

#include <fstream>
#include <iostream>
#include <set>
#include <thread>

#include "common/lcm_bus.hpp"
#include "tests/integration/run_command.hpp"
#include "tests/rigs/real_time_support.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;
using a3::test::joined;
using a3::test::Outcome;
using a3::test::outcome_of;
using a3::test::part_of_run;
using a3::test::read_json;
using a3::test::RunningRig;

void expect_same_outcome(const std::string& scenario, const std::string& think_time, double real_time_factor) {
  RunOptions v = a3::test::virtual_run(scenario, "virtual-" + think_time);
  v.think_time = think_time;
  RunOptions r = v;
  r.runtime = Runtime::kReal;
  r.real_time_factor = real_time_factor;
  r.out_dir = v.out_dir.string() + "-real";
  const RunResult a = a3::test::run(v);
  const auto t0 = std::chrono::steady_clock::now();
  const RunResult b = a3::test::run(r);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Outcome x = outcome_of(a.episode), y = outcome_of(b.episode);
  std::cout << scenario << " think " << think_time << ": virtual " << x.status << ", real time (factor "
            << real_time_factor << ", " << wall_s << " s wall) " << y.status << "; SP " << x.sp << " / " << y.sp
            << "\n";
  EXPECT_EQ(x.status, "completed");
  a3::test::expect_same_outcome(x, y);
  // Real time really ran on the wall clock at the factor asked for.
  const double mission_s = b.episode["_rig"]["mission_time_s"].get<double>();
  EXPECT_GT(wall_s, 0.8 * mission_s / real_time_factor);
  fs::remove_all(v.out_dir);
  fs::remove_all(r.out_dir);
}

TEST(RealTimeRig, TheConflictMissionEndsAsInVirtualTimeWithAQuickAgent) {
  A3_REQUIRE_MULTICAST();
  expect_same_outcome("traffic-conflict", "0", 6.0);
}

TEST(RealTimeRig, TheConflictMissionEndsAsInVirtualTimeWithASlowAgent) {
  A3_REQUIRE_MULTICAST();
  // Think 60 s: turns a minute apart; the swarm asked in every turn in the air yields, the same
  // way in both runtimes.
  expect_same_outcome("traffic-conflict", "60", 8.0);
}

TEST(RunCommand, BadUsageExitsWith2NamingTheProblem) {
  using a3::test::a3rig;
  using a3::test::run_command;
  const a3::test::TempDir dir("run-usage");
  const std::string never = (dir.path() / "never").string();
  auto r = run_command(a3rig() + " run --scenario no-such-scenario --runtime virtual --out " + never, true);
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find("no-such-scenario"), std::string::npos) << r.output;
  r = run_command(a3rig() + " run --processes --runtime virtual --out " + never, true);
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find("--processes"), std::string::npos) << r.output;
  r = run_command(a3rig() + " run --think-time sometimes --runtime virtual --out " + never, true);
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find("sometimes"), std::string::npos) << r.output;
  r = run_command("env -u A3_LLM_BASE_URL " + a3rig() + " run --agent llm --runtime virtual --out " + never, true);
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find("no LLM endpoint"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(never)) << "a usage error wrote output";
}

TEST(RunCommand, AnInterruptedRealTimeRunIsWrittenWithItsStatus) {
  A3_REQUIRE_MULTICAST();
  const a3::test::TempDir dir("run-interrupted");
  const fs::path out = dir.path() / "out";
  RunningRig rig({a3::test::a3rig(), "run", "--scenario", "survey-field", "--rtf", "4", "--out", out.string()},
                 dir.path() / "output.txt");
  ASSERT_TRUE(rig.wait_for_output("turn  3", 60.0)) << rig.text();
  ::kill(rig.pid, SIGINT);
  EXPECT_EQ(rig.wait_exit(60.0), 3) << rig.text();
  for (const char* f : {"episode.json", "episode.lcmlog", "trajectory.png"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f << "\n" << rig.text();
  }
  const json e = read_json(out / "episode.json");
  EXPECT_EQ(e["_rig"]["status"], "interrupted");
  EXPECT_GE(e["dialogue"].size(), 3u);
  EXPECT_FALSE(e["success"].get<bool>());
  // The LCM log is one standard tools open: it starts with LCM's sync word 0xEDA1DA01.
  std::ifstream log(out / "episode.lcmlog", std::ios::binary);
  unsigned char head[4] = {};
  log.read(reinterpret_cast<char*>(head), 4);
  EXPECT_EQ(head[0], 0xED);
  EXPECT_EQ(head[1], 0xA1);
  EXPECT_EQ(head[2], 0xDA);
  EXPECT_EQ(head[3], 0x01);
}

TEST(RunCommand, ANodeProcessThatDiesEndsTheRunNamingIt) {
  A3_REQUIRE_MULTICAST();
  const a3::test::TempDir dir("run-processes");
  const fs::path out = dir.path() / "out";
  RunningRig rig({a3::test::a3rig(), "run", "--processes", "--scenario", "survey-field", "--rtf", "2", "--out",
                  out.string()},
                 dir.path() / "output.txt");
  ASSERT_TRUE(rig.wait_for_output("turn  2", 90.0)) << rig.text();
  const pid_t run_pid = rig.pid;
  const pid_t fc = part_of_run(run_pid, "fc");
  ASSERT_GT(fc, 0) << "no `a3rig node part fc` process of run " << run_pid;
  ::kill(fc, SIGKILL);
  EXPECT_EQ(rig.wait_exit(60.0), 4) << rig.text();
  EXPECT_NE(rig.text().find("node_failed: fc"), std::string::npos) << rig.text();
  const json e = read_json(out / "episode.json");
  EXPECT_EQ(e["_rig"]["status"].get<std::string>().rfind("node_failed: fc", 0), 0u) << e["_rig"]["status"];
  // No part outlives the run.
  for (const char* part : {"dynamics", "bridge", "linkemu", "vehicle"}) EXPECT_EQ(part_of_run(run_pid, part), -1) << part;
}

}  // namespace
}  // namespace a3::rigs
