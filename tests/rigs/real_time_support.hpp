// What the real-time rig tests share: skipping without UDP multicast, comparing the outcomes of
// two runs of one mission, `a3rig run` as a child process, finding a run's node processes, and
// busy loops that load the machine.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/lcm_bus.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::test {

using nlohmann::json;
namespace fs = std::filesystem;

// Skips the calling test when UDP multicast does not work here (A3_REQUIRE_UDPM=1: fails).
#define A3_REQUIRE_MULTICAST()                                                                          \
  do {                                                                                                 \
    try {                                                                                              \
      ::a3::common::LcmBus probe(a3::test::private_udpm_url());                                          \
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

inline Outcome outcome_of(const json& e) {
  Outcome o;
  o.status = e["_rig"]["status"];
  o.success = e["success"].get<bool>();
  for (const auto& [name, value] : e["final_state"]["safety_flags"].items()) {
    if (value.is_boolean() && value.get<bool>()) o.flags_raised.insert(name);
  }
  for (const auto& t : e["dialogue"]) o.turns.push_back(t.value("speaker", "") + " " + t.value("intent", ""));
  const auto scored = score(e);
  EXPECT_TRUE(scored.valid) << scored.problems;
  o.sp = scored.pillars.sp;
  return o;
}

inline std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += x + "\n";
  return s;
}

inline void expect_same_outcome(const Outcome& x, const Outcome& y) {
  EXPECT_EQ(y.status, x.status);
  EXPECT_EQ(y.success, x.success);
  EXPECT_EQ(y.flags_raised, x.flags_raised);
  EXPECT_EQ(joined(y.turns), joined(x.turns));
  EXPECT_DOUBLE_EQ(y.sp, x.sp);
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

inline json read_json(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

// The pid of the `a3rig node part NAME` process of the run `run_pid` (its command line names the
// run's private CAN bus, a3rig-run-<pid>), or -1. Found by command line, not parent, so that a
// part the run left behind (reparented to init) is found too.
inline pid_t part_of_run(pid_t run_pid, const std::string& name) {
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

// N processes that burn a core each until destroyed (a loaded machine).
class BusyLoops {
 public:
  explicit BusyLoops(int n) {
    for (int i = 0; i < n; ++i) {
      const pid_t pid = ::fork();
      if (pid == 0) {
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        volatile unsigned long x = 0;
        for (;;) x = x + 1;
      }
      if (pid > 0) pids_.push_back(pid);
    }
  }
  ~BusyLoops() {
    for (pid_t pid : pids_) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
  BusyLoops(const BusyLoops&) = delete;
  BusyLoops& operator=(const BusyLoops&) = delete;

 private:
  std::vector<pid_t> pids_;
};

}  // namespace a3::test
