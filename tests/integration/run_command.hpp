// Runs a shell command for an end-to-end test and returns its exit status and output.
#pragma once

#include <signal.h>
#include <sys/wait.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

namespace a3::test {

struct CommandResult {
  int exit_status = -1;
  std::string output;  // stdout, or stdout+stderr with merge_stderr
};

inline CommandResult run_command(const std::string& command, bool merge_stderr = false) {
  CommandResult result;
  const std::string full = command + (merge_stderr ? " 2>&1" : "");
  FILE* pipe = ::popen(full.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

inline std::string a3rig() { return std::string(A3_BINARY_DIR) + "/a3rig"; }

inline std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A child's exit status after waiting at most timeout_s (then SIGKILL: -1); waited_s is how long.
inline int await_exit(pid_t pid, double timeout_s, double& waited_s) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    waited_s = std::chrono::duration<double>(Clock::now() - t0).count();
    if (waited_s > timeout_s) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  waited_s = std::chrono::duration<double>(Clock::now() - t0).count();
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace a3::test
