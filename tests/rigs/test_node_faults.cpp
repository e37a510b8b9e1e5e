// A node process that freezes (SIGSTOP) or dies (SIGKILL) in `a3rig run --processes` ends the
// run as node_failed naming it with its pid, exit status 4, the episode written: a frozen one
// after 3 s without statistics, a dead one at once. Real time (labels realtime, faults; SERIAL).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "tests/integration/run_command.hpp"

namespace a3 {
namespace {

using a3::test::await_exit;

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

pid_t start_run(const fs::path& out, const fs::path& log) {
  const std::string exe = std::string(A3_BINARY_DIR) + "/a3rig";
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::execl(exe.c_str(), exe.c_str(), "run", "--processes", "--no-plot", "--no-lcm-log", "--out", out.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

// The pid of the child `a3rig node part <part>` of `parent`, or -1.
pid_t part_pid(pid_t parent, const std::string& part) {
  std::istringstream children(read_text("/proc/" + std::to_string(parent) + "/task/" + std::to_string(parent) + "/children"));
  for (pid_t child; children >> child;) {
    std::string cmdline = read_text("/proc/" + std::to_string(child) + "/cmdline");
    for (char& c : cmdline) c = c == '\0' ? ' ' : c;
    if (cmdline.find("node part " + part + " ") != std::string::npos) return child;
  }
  return -1;
}

// Flies until the parts are up and the first turn is in, sends `signal` to `part`, and checks
// how the run ended. Returns the status line.
std::string fault_part(const std::string& part, int signal, double max_end_s) {
  const fs::path out = fs::path(::testing::TempDir()) / ("a3rig-node-fault-" + part + "-" + std::to_string(::getpid()));
  const fs::path log = out.string() + ".log";
  fs::remove_all(out);
  const pid_t run = start_run(out, log);
  pid_t child = -1;
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < deadline && read_text(log).find("turn  1") == std::string::npos) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  child = part_pid(run, part);
  EXPECT_GT(child, 0) << part << ": " << read_text(log);
  if (child <= 0) {
    ::kill(run, SIGKILL);
    ::waitpid(run, nullptr, 0);
    return "";
  }
  ::kill(child, signal);
  double waited_s = 0.0;
  const int exit_status = await_exit(run, 60.0, waited_s);
  std::printf("%s %s: the run ended %.2f s later\n", part.c_str(), signal == SIGSTOP ? "SIGSTOP" : "SIGKILL", waited_s);
  if (signal == SIGSTOP) ::kill(child, SIGKILL);  // should it have outlived the run
  EXPECT_EQ(exit_status, 4) << part << ": " << read_text(log);
  EXPECT_LT(waited_s, max_end_s) << part;
  const auto episode = nlohmann::json::parse(read_text(out / "episode.json"), nullptr, false);
  EXPECT_TRUE(episode.is_object()) << part << ": no episode written";
  const std::string status = episode.is_object() ? episode["_rig"].value("status", "") : "";
  EXPECT_EQ(status.rfind("node_failed: ", 0), 0u) << status;
  EXPECT_NE(status.find("(pid " + std::to_string(child) + ")"), std::string::npos) << part << ": " << status;
  fs::remove_all(out);
  fs::remove(log);
  return status;
}

// Detection within 3 s; then the other children stop and the episode is written (about 1-2 s).
constexpr double kFrozenRunEnds_s = 3.0 + 3.0;
constexpr double kDeadRunEnds_s = 3.0;

TEST(NodeFaults, AFrozenNodeProcessEndsTheRunNamingItWithin3Seconds) {
  for (const std::string part : {"dynamics", "fc", "vehicle"}) {
    const std::string status = fault_part(part, SIGSTOP, kFrozenRunEnds_s);
    EXPECT_NE(status.find("is unresponsive: no statistics for 3 s of wall time"), std::string::npos) << status;
  }
}

TEST(NodeFaults, AKilledNodeProcessEndsTheRunNamingItAtOnce) {
  for (const std::string part : {"bridge", "linkemu"}) {
    const std::string status = fault_part(part, SIGKILL, kDeadRunEnds_s);
    EXPECT_NE(status.find(part + " (pid "), std::string::npos) << status;
    EXPECT_NE(status.find("killed by signal 9"), std::string::npos) << status;
  }
}

}  // namespace
}  // namespace a3
