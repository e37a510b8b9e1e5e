// `a3rig run` as a child process per cell (posix_spawn), its output in the cell's run.log.
#include "rigs/sweep/cell_runner.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "common/atomic_file.hpp"
#include "rigs/run/run_flags.hpp"

extern char** environ;

namespace a3::rigs::sweep {
namespace {

std::string format_seconds(double s) {
  std::ostringstream out;
  out << s;
  return out.str();
}

// Waits up to 10 ms for the child to end: on its pidfd, which wakes the moment it exits, where
// the kernel has pidfds (Linux 5.3), else a plain sleep.
class ChildExitWait {
 public:
  // By system call: glibc 2.36's <sys/pidfd.h> declares pidfd_open without C linkage for C++.
  explicit ChildExitWait(pid_t pid) : pidfd_(static_cast<int>(::syscall(SYS_pidfd_open, pid, 0))) {}
  ~ChildExitWait() {
    if (pidfd_ >= 0) ::close(pidfd_);
  }
  ChildExitWait(const ChildExitWait&) = delete;
  ChildExitWait& operator=(const ChildExitWait&) = delete;
  void wait() const {
    if (pidfd_ < 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      return;
    }
    pollfd exited{pidfd_, POLLIN, 0};
    ::poll(&exited, 1, 10);
  }

 private:
  int pidfd_;
};

}  // namespace

ChildProcessCellRunner::ChildProcessCellRunner(ChildProcessOptions options) : options_(std::move(options)) {
  if (options_.runtime != "virtual" && options_.runtime != "real") {
    throw std::invalid_argument("--runtime '" + options_.runtime + "': expected virtual or real");
  }
  if (::access(options_.a3rig_exe.c_str(), X_OK) != 0) {
    throw std::invalid_argument("a3rig program " + options_.a3rig_exe.string() + " is not executable");
  }
}

std::vector<std::string> ChildProcessCellRunner::command(const SweepCell& cell, const std::filesystem::path& dir) const {
  RunOptions o;
  o.runtime = options_.runtime == "real" ? Runtime::kReal : Runtime::kVirtual;
  o.scenario = cell.scenario;
  o.agent = cell.agent;
  o.think_time = cell.think_time;
  o.slice = linkemu::parse_slice(cell.slice);
  o.seed = cell.seed;
  o.out_dir = dir;
  o.write_lcm_log = false;
  o.write_plot = false;
  o.quiet = true;
  o.real_time_factor = options_.real_time_factor;
  std::vector<std::string> argv = {options_.a3rig_exe.string(), "run"};
  for (std::string& a : to_argv(o, {RunFlag::kRuntime, RunFlag::kScenario, RunFlag::kAgent, RunFlag::kThinkTime,
                                    RunFlag::kSlice, RunFlag::kSeed, RunFlag::kOut, RunFlag::kNoLcmLog,
                                    RunFlag::kNoPlot, RunFlag::kQuiet})) {
    argv.push_back(std::move(a));
  }
  if (o.runtime == Runtime::kReal) {
    for (std::string& a : to_argv(o, {RunFlag::kRtf})) argv.push_back(std::move(a));
  }
  argv.insert(argv.end(), options_.extra_run_args.begin(), options_.extra_run_args.end());
  return argv;
}

CellRunOutcome ChildProcessCellRunner::run(const SweepCell& cell, const std::filesystem::path& dir,
                                           const std::atomic<bool>& stop) {
  const auto log_path = dir / "run.log";
  const std::vector<std::string> args = command(cell, dir);
  std::string command_line = "$";
  for (const auto& a : args) command_line += " " + a;
  try {
    common::write_file_atomically(log_path, command_line + "\n");  // the child appends its output
  } catch (const common::OutputError& e) {
    return {false, e.what()};
  }
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(), O_WRONLY | O_APPEND, 0);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  // A process group of its own: a terminal's Ctrl-C reaches the sweep only, which forwards it
  // once (a second SIGINT would end `a3rig run` before it writes its episode).
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  pid_t pid = 0;
  const int spawn_error = posix_spawn(&pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawn_error != 0) {
    return {false, "could not start " + args[0] + ": " + std::strerror(spawn_error)};
  }

  const auto start = std::chrono::steady_clock::now();
  bool stop_forwarded = false, timed_out = false;
  std::chrono::steady_clock::time_point killed_at{};
  int wait_status = 0;
  const ChildExitWait child_exit(pid);
  while (true) {
    const pid_t done = ::waitpid(pid, &wait_status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) return {false, std::string("waitpid failed: ") + std::strerror(errno)};
    const auto now = std::chrono::steady_clock::now();
    const double elapsed_s = std::chrono::duration<double>(now - start).count();
    if (stop.load() && !stop_forwarded) {
      ::kill(pid, SIGINT);  // the run ends early and writes its episode (status interrupted)
      stop_forwarded = true;
    }
    if (!timed_out && options_.cell_timeout_s > 0.0 && elapsed_s > options_.cell_timeout_s) {
      ::kill(pid, SIGTERM);
      timed_out = true;
      killed_at = now;
    }
    if (timed_out && now - killed_at > std::chrono::seconds(10)) ::kill(pid, SIGKILL);
    child_exit.wait();
  }
  const std::string see_log = " (see " + log_path.string() + ")";
  if (timed_out) {
    return {false, "timed out after " + format_seconds(options_.cell_timeout_s) + " s wall" + see_log};
  }
  if (WIFSIGNALED(wait_status)) {
    return {false, "a3rig run died of signal " + std::to_string(WTERMSIG(wait_status)) + " (" +
                       strsignal(WTERMSIG(wait_status)) + ")" + see_log};
  }
  const int code = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
  // 9: never_flew, a flown episode (written) in which the vehicle stayed on the ground: the
  // cell's result, a failure of its agent, not of the run.
  if (code != 0 && code != 9) return {false, "a3rig run exited with status " + std::to_string(code) + see_log};
  return {true, ""};
}

}  // namespace a3::rigs::sweep
