// The command line's contract: a usage error of any subcommand exits 2 with one line on stderr
// naming the command, the flag and the allowed range in human numbers (no 309-digit bound);
// --help and --version exit 0; an output folder that cannot be a folder is refused up front.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace a3 {
namespace {

struct Outcome {
  int exit_status = -1;
  std::string output;  // stdout and stderr
};

Outcome a3rig(const std::string& arguments) {
  const std::string command = std::string(A3_BINARY_DIR) + "/a3rig " + arguments + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  Outcome o;
  if (pipe == nullptr) return o;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) o.output += buffer;
  const int status = ::pclose(pipe);
  o.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

int lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

void expect_usage_error(const std::string& arguments, const std::string& line) {
  const Outcome o = a3rig(arguments);
  EXPECT_EQ(o.exit_status, 2) << arguments << ": " << o.output;
  EXPECT_EQ(lines(o.output), 1) << arguments << ": " << o.output;
  EXPECT_EQ(o.output.rfind(line, 0), 0u) << arguments << ": " << o.output;
}

TEST(CliUsage, OutOfRangeNumbersNameTheFlagAndTheBoundsInOneLine) {
  expect_usage_error("run --rtf -1", "a3rig run: --rtf: must be > 0 (got -1)");
  expect_usage_error("run --max-turns 500", "a3rig run: --max-turns: must be from 2 to 100 (got 500)");
  expect_usage_error("mcp --rtf 0", "a3rig mcp: --rtf: must be > 0 (got 0)");
  expect_usage_error("sweep --jobs 0", "a3rig sweep: --jobs: must be from 1 to 1024 (got 0)");
  expect_usage_error("sweep --cell-timeout -5", "a3rig sweep: --cell-timeout: must be >= 0 (got -5)");
  expect_usage_error("validate --max-file-mb 0 .", "a3rig validate: --max-file-mb: must be > 0 (got 0)");
  expect_usage_error("node part --rtf -2 dynamics", "a3rig node part: --rtf: must be > 0 (got -2)");
}

TEST(CliUsage, WordsWhereNumbersGoAndUnknownFlagsAreUsageErrors) {
  expect_usage_error("run --rtf fast", "a3rig run: --rtf: must be a number > 0 (got 'fast')");
  expect_usage_error("run --no-such-flag", "a3rig run: The following argument was not expected: --no-such-flag");
  expect_usage_error("score --threads", "a3rig score: --threads:");
  expect_usage_error("", "a3rig: A subcommand is required");
}

TEST(CliUsage, AnOutputFolderThatIsAFileIsRefused) {
  expect_usage_error("run --out /etc/passwd", "a3rig run: --out: /etc/passwd is a file, not a folder");
  expect_usage_error("sweep --out /etc/passwd/x",
                     "a3rig sweep: --out: cannot create /etc/passwd/x: /etc/passwd is a file, not a folder");
}

TEST(CliUsage, HelpAndVersionExitZero) {
  for (const std::string arguments : {"--help", "run --help", "validate --help", "--version"}) {
    const Outcome o = a3rig(arguments);
    EXPECT_EQ(o.exit_status, 0) << arguments << ": " << o.output;
    EXPECT_FALSE(o.output.empty()) << arguments;
  }
}

}  // namespace
}  // namespace a3
