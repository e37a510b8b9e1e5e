// Starting, synchronising and supervising the rig's child processes.
#include "rigs/run/rig_processes.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "rigs/run/run_flags.hpp"

namespace a3::rigs {
namespace {

std::string format_double(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

}  // namespace

std::vector<std::string> RigProcesses::child_arguments(RigPart part, const RunOptions& o, const std::string& lcm_url,
                                                       const std::string& can_spec) {
  RunOptions child = o;
  child.lcm_url = lcm_url;
  child.can = can_spec;
  std::vector<std::string> args = {"node", "part", to_string(part)};
  for (std::string& a : to_argv(child, {RunFlag::kScenario, RunFlag::kSeed, RunFlag::kRtf, RunFlag::kSync,
                                        RunFlag::kLcmUrl, RunFlag::kCan, RunFlag::kIntegrator, RunFlag::kDynamicsRate,
                                        RunFlag::kSharedDir, RunFlag::kSlice})) {
    args.push_back(std::move(a));
  }
  return args;
}

RigProcesses::RigProcesses(const std::filesystem::path& exe, const std::vector<RigPart>& parts, const RunOptions& o,
                           const std::string& lcm_url, const std::string& can_spec) {
  const pid_t parent = ::getpid();
  for (RigPart part : parts) {
    int to_child[2], from_child[2];
    if (::pipe2(to_child, O_CLOEXEC) != 0 || ::pipe2(from_child, O_CLOEXEC) != 0) {
      stop(0.0);
      throw std::runtime_error("starting the " + to_string(part) + " process: pipe: " + std::strerror(errno));
    }
    std::vector<std::string> args = child_arguments(part, o, lcm_url, can_spec);
    args.insert(args.begin(), exe.string());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0) {
      stop(0.0);
      throw std::runtime_error("starting the " + to_string(part) + " process: fork: " + std::strerror(errno));
    }
    if (pid == 0) {
      // The child: stdin from us, stdout to us, stderr shared; dies with us.
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (::getppid() != parent) ::_exit(1);
      ::dup2(to_child[0], STDIN_FILENO);
      ::dup2(from_child[1], STDOUT_FILENO);
      ::execv(argv[0], argv.data());
      const char* message = "a3rig run --processes: exec failed\n";
      (void)!::write(STDERR_FILENO, message, std::strlen(message));
      ::_exit(127);
    }
    ::close(to_child[0]);
    ::close(from_child[1]);
    Child c;
    c.part = part;
    c.pid = pid;
    c.go_fd = to_child[1];
    c.ready_fd = from_child[0];
    children_.push_back(c);
  }
}

RigProcesses::~RigProcesses() { stop(); }

std::string RigProcesses::wait_ready(double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (Child& c : children_) {
    std::string line;
    while (!c.ready) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) return to_string(c.part) + " did not say ready within " + format_double(timeout_s) + " s";
      pollfd p{c.ready_fd, POLLIN, 0};
      const int n = ::poll(&p, 1, static_cast<int>(std::min<int64_t>(left.count(), 200)));
      if (n < 0 && errno != EINTR) return to_string(c.part) + ": poll: " + std::strerror(errno);
      if (n <= 0) continue;
      char ch;
      const ssize_t got = ::read(c.ready_fd, &ch, 1);
      if (got == 1) {
        if (ch == '\n') {
          if (line == "ready") {
            c.ready = true;
          } else {
            return to_string(c.part) + " said '" + line + "' instead of ready";
          }
        } else {
          line.push_back(ch);
        }
      } else if (got == 0) {
        const std::string why = check();
        return why.empty() ? to_string(c.part) + " closed its output before it was ready" : why;
      }
    }
  }
  return "";
}

void RigProcesses::go(int64_t epoch_mono_ns) {
  const std::string line = "go " + std::to_string(epoch_mono_ns) + "\n";
  for (Child& c : children_) {
    if (c.go_fd >= 0) (void)!::write(c.go_fd, line.data(), line.size());
  }
}

std::string RigProcesses::describe_exit(const Child& c) {
  const std::string who = to_string(c.part) + " (pid " + std::to_string(c.pid) + ")";
  if (WIFEXITED(c.wait_status)) return who + " exited with status " + std::to_string(WEXITSTATUS(c.wait_status));
  if (WIFSIGNALED(c.wait_status)) {
    return who + " was killed by signal " + std::to_string(WTERMSIG(c.wait_status)) + " (" +
           ::strsignal(WTERMSIG(c.wait_status)) + ")";
  }
  return who + " ended";
}

std::string RigProcesses::check() {
  for (Child& c : children_) {
    if (c.exited || c.pid < 0) continue;
    int status = 0;
    if (::waitpid(c.pid, &status, WNOHANG) == c.pid) {
      c.exited = true;
      c.wait_status = status;
      return describe_exit(c);
    }
  }
  for (const Child& c : children_) {
    if (c.exited) return describe_exit(c);
  }
  return "";
}

void RigProcesses::stop(double grace_s) {
  for (Child& c : children_) {
    if (!c.exited && c.pid > 0) {
      ::kill(c.pid, SIGTERM);
      ::kill(c.pid, SIGCONT);  // a frozen (SIGSTOP) child takes its SIGTERM now, not after the grace time
    }
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace_s);
  for (Child& c : children_) {
    while (!c.exited && c.pid > 0) {
      int status = 0;
      const pid_t r = ::waitpid(c.pid, &status, WNOHANG);
      if (r == c.pid || (r < 0 && errno == ECHILD)) {
        c.exited = true;
        c.wait_status = status;
      } else if (std::chrono::steady_clock::now() >= deadline) {
        ::kill(c.pid, SIGKILL);
        ::waitpid(c.pid, &status, 0);
        c.exited = true;
        c.wait_status = status;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    }
    if (c.go_fd >= 0) ::close(c.go_fd);
    if (c.ready_fd >= 0) ::close(c.ready_fd);
    c.go_fd = c.ready_fd = -1;
  }
}

}  // namespace a3::rigs
