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
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Skips the calling test when UDP multicast does not work here (A3_REQUIRE_UDPM=1: fails).
#define A3_REQUIRE_MULTICAST()                                                                          \
  do {                                                                                                 \
    try {                                                                                              \
      common::LcmBus probe(a3::test::private_udpm_url());                                             \
      probe.check_loopback();                                                                          \
    } catch (const std::exception& e) {                                                                \
      const char* require = std::getenv("A3_REQUIRE_UDPM");                                            \
      if (require != nullptr && std::string(require) == "1") FAIL() << e.what();                      \
      GTEST_SKIP() << "LCM UDP multicast unavailable (" << e.what() << "); run scripts/lcm-loopback.sh as root"; \
    }                                                                                                  \
  } while (0)

// What decides an episode's outcome, for comparing two runs of one mission.
struct Outcome {
  std::string status;
  bool success = false;
  std::set<std::string> flags_raised;
  std::vector<std::string> turns;  // "speaker intent"
  double sp = 0.0;
};

Outcome outcome_of(const json& e) {
  Outcome o;
  o.status = e["_rig"]["status"];
  o.success = e["success"].get<bool>();
  for (const auto& [name, value] : e["final_state"]["safety_flags"].items()) {
    if (value.is_boolean() && value.get<bool>()) o.flags_raised.insert(name);
  }
  for (const auto& t : e["dialogue"]) o.turns.push_back(t.value("speaker", "") + " " + t.value("intent", ""));
  const auto scored = a3::test::score(e);
  EXPECT_TRUE(scored.valid) << scored.problems;
  o.sp = scored.pillars.sp;
  return o;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += x + "\n";
  return s;
}

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
  EXPECT_EQ(y.status, x.status);
  EXPECT_EQ(y.success, x.success);
  EXPECT_EQ(y.flags_raised, x.flags_raised);
  EXPECT_EQ(joined(y.turns), joined(x.turns));
  EXPECT_DOUBLE_EQ(y.sp, x.sp);
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
  // Think 60 s: the agent misses the conflict; the breach is measured in both runtimes.
  expect_same_outcome("traffic-conflict", "60", 8.0);
}

// `a3rig run` as a child process with its output in a file.
struct RunningRig {
  pid_t pid = -1;
  fs::path output;
  RunningRig(const std::vector<std::string>& args, const fs::path& output_file) : output(output_file) {
    pid = ::fork();
    if (pid == 0) {
      ::setpgid(0, 0);
      const int fd = ::open(output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      std::vector<char*> argv;
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  std::string text() const {
    std::ifstream in(output);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  bool wait_for_output(const std::string& needle, double timeout_s) const {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < end) {
      if (text().find(needle) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
  }
  int wait_exit(double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    int status = 0;
    while (std::chrono::steady_clock::now() < end) {
      if (::waitpid(pid, &status, WNOHANG) == pid) {
        pid = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return -1;
  }
  ~RunningRig() {
    if (pid > 0) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
};

json read_json(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
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

// The pid of the `a3rig node part NAME` process of the run `run_pid` (its command line names the
// run's private CAN bus, a3rig-run-<pid>), or -1. Found by command line, not parent, so that a
// part the run left behind (reparented to init) is found too.
pid_t part_of_run(pid_t run_pid, const std::string& name) {
  const std::string bus = "a3rig-run-" + std::to_string(run_pid) + " ";
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string pid_text = entry.path().filename();
    if (pid_text.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream cmd(entry.path() / "cmdline");
    std::string args(std::istreambuf_iterator<char>(cmd), {});
    for (char& c : args) c = c == '\0' ? ' ' : c;
    if (args.find("node part " + name + " ") != std::string::npos && args.find(bus) != std::string::npos) {
      return static_cast<pid_t>(std::stol(pid_text));
    }
  }
  return -1;
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
