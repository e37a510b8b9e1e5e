// posix_spawnp with two pipes, read with poll until both close.
#include "rigs/sweep/captured_command.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace a3::rigs::sweep {
namespace {

struct Pipe {
  int read_fd = -1;
  int write_fd = -1;
  Pipe() {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    read_fd = fds[0];
    write_fd = fds[1];
  }
  ~Pipe() {
    if (read_fd >= 0) ::close(read_fd);
    if (write_fd >= 0) ::close(write_fd);
  }
  void close_write() {
    ::close(write_fd);
    write_fd = -1;
  }
};

// Reads both pipes until the program closes them.
void drain(Pipe& out_pipe, Pipe& err_pipe, CapturedOutput& captured) {
  pollfd fds[2] = {{out_pipe.read_fd, POLLIN, 0}, {err_pipe.read_fd, POLLIN, 0}};
  std::string* sinks[2] = {&captured.out, &captured.err};
  int open_count = 2;
  char buffer[4096];
  while (open_count > 0) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        sinks[i]->append(buffer, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        fds[i].fd = -1;
        --open_count;
      }
    }
  }
}

}  // namespace

CapturedOutput ProcessCommandRunner::run(const std::vector<std::string>& argv) {
  if (argv.empty()) throw std::invalid_argument("no program to run");
  Pipe out_pipe;
  Pipe err_pipe;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out_pipe.write_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err_pipe.write_fd, STDERR_FILENO);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, argv[0].c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned == ENOENT) throw std::runtime_error(argv[0] + ": not found on PATH");
  if (spawned != 0) throw std::runtime_error(argv[0] + ": cannot start: " + std::strerror(spawned));
  out_pipe.close_write();
  err_pipe.close_write();
  CapturedOutput captured;
  drain(out_pipe, err_pipe, captured);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  captured.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return captured;
}

}  // namespace a3::rigs::sweep
