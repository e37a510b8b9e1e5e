// Ctrl-C during an LLM call that hangs, on the a3rig program in real time: the run ends within
// 3 s with exit status 3, and the episode on disk has status interrupted and the interrupted
// turn with its attempt log (outcome "interrupted"); a second Ctrl-C exits 130 at once, saying
// that nothing more is written. The endpoint answers the check before take-off, then hangs.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "tests/agent_llm/silent_endpoint.hpp"
#include "tests/integration/run_command.hpp"

namespace a3 {
namespace {

using a3::test::await_exit;

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct StartedRun {
  pid_t pid = -1;
  fs::path out;
  fs::path log;
};

// `a3rig run --agent llm` against `endpoint`, output to a fresh folder, stdout and stderr to a log.
StartedRun start_run(const test::SilentEndpoint& endpoint, const std::string& tag) {
  StartedRun r;
  r.out = fs::path(::testing::TempDir()) / ("a3rig-ctrl-c-" + tag + "-" + std::to_string(::getpid()));
  fs::remove_all(r.out);
  r.log = r.out.string() + ".log";
  const std::string exe = std::string(A3_BINARY_DIR) + "/a3rig";
  const std::string base_url = endpoint.base_url();
  r.pid = ::fork();
  if (r.pid == 0) {
    const int fd = ::open(r.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::execl(exe.c_str(), exe.c_str(), "run", "--agent", "llm", "--llm-base-url", base_url.c_str(), "--llm-model", "m",
            "--llm-timeout", "30", "--no-plot", "--no-lcm-log", "--out", r.out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return r;
}

// Waits until the endpoint has had `n` requests (the check, then the first turn's call).
bool await_requests(const test::SilentEndpoint& endpoint, int n, double timeout_s) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (Clock::now() < deadline) {
    if (endpoint.requests() >= n) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(LlmFaultsRealTime, CtrlCDuringAHangingCallEndsTheRunWithTheInterruptedTurnWritten) {
  test::SilentEndpoint endpoint(1);
  const StartedRun r = start_run(endpoint, "once");
  ASSERT_TRUE(await_requests(endpoint, 2, 30.0)) << read_text(r.log);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the call is in flight
  ::kill(r.pid, SIGINT);
  double waited_s = 0.0;
  const int exit_status = await_exit(r.pid, 30.0, waited_s);
  std::printf("a3rig run ended %.2f s after Ctrl-C\n", waited_s);
  EXPECT_EQ(exit_status, 3) << read_text(r.log);
  EXPECT_LT(waited_s, 3.0) << "the hanging call (timeout 30 s) held the stop";
  const auto episode = nlohmann::json::parse(read_text(r.out / "episode.json"), nullptr, false);
  ASSERT_TRUE(episode.is_object()) << read_text(r.log);
  EXPECT_EQ(episode["_rig"]["status"], "interrupted");
  ASSERT_FALSE(episode["dialogue"].empty()) << "the interrupted turn is in the episode";
  EXPECT_EQ(episode["dialogue"][0]["intent"], "interrupted");
  const auto& log = episode["_rig"]["turns"][0]["attempt_log"];
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0]["outcome"], "interrupted");
  fs::remove_all(r.out);
  fs::remove(r.log);
}

TEST(LlmFaultsRealTime, ASecondCtrlCExits130AtOnceSayingNothingMoreIsWritten) {
  test::SilentEndpoint endpoint(1);
  const StartedRun r = start_run(endpoint, "twice");
  ASSERT_TRUE(await_requests(endpoint, 2, 30.0)) << read_text(r.log);
  // Two signals sent together would be one (standard signals do not queue); the first stop takes
  // about 0.1 s, so 10 ms later the program is still stopping.
  ::kill(r.pid, SIGINT);
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(r.pid, SIGINT);
  double waited_s = 0.0;
  const int exit_status = await_exit(r.pid, 30.0, waited_s);
  EXPECT_EQ(exit_status, 130) << read_text(r.log);
  EXPECT_LT(waited_s, 1.0);
  EXPECT_NE(read_text(r.log).find("a3rig: second interrupt: exiting now (status 130); nothing more is written"),
            std::string::npos)
      << read_text(r.log);
  fs::remove_all(r.out);
  fs::remove(r.log);
}

}  // namespace
}  // namespace a3
