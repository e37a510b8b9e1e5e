// gnuplot strings and runs (gnuplot.hpp).
#include "common/gnuplot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace a3::common {

std::string gnuplot_string(std::string_view text) {
  // gnuplot 5.4's scanner misreads a doubled quote at a string's start or two in a row (the
  // literal '''x' is an error), so a quote is joined in by concatenation: 'it'."'".'s'.
  std::string out = "'";
  for (const char c : text) {
    if (c == '\'') {
      out += "'.\"'\".'";
    } else {
      out += (c == '\n' || c == '\r') ? ' ' : c;
    }
  }
  return out + "'";
}

std::string gnuplot_data_label(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) out += (c == '"' || c == '\t' || c == '\n' || c == '\r') ? ' ' : c;
  return out + "\"";
}

bool gnuplot_found() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string program = (dir.empty() ? std::string(".") : dir) + "/gnuplot";
    if (::access(program.c_str(), X_OK) == 0) return true;
  }
  return false;
}

namespace {

std::string log_text(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

void run_gnuplot(const std::filesystem::path& script, const std::filesystem::path& log,
                 const std::vector<std::string>& assignments) {
  std::vector<std::string> words = {"gnuplot"};
  for (const std::string& assignment : assignments) {
    words.push_back("-e");
    words.push_back(assignment);
  }
  words.push_back(script.string());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int spawn_error = ::posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error != 0) {
    throw std::runtime_error(std::string("cannot run gnuplot (") + std::strerror(spawn_error) +
                             "); install it with: apt-get install gnuplot-nox");
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("gnuplot failed on " + script.string() + ": " + log_text(log));
  }
}

}  // namespace a3::common
