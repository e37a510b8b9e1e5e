// The command line's contract: a usage error of any subcommand exits 2 with one line on stderr
// naming the command, the flag and the allowed range in human numbers (no 309-digit bound);
// --help and --version exit 0; an output folder that cannot be a folder is refused up front.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>
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

TEST(CliUsage, AnInProcessLcmUrlIsRefusedInRealTimeInsteadOfHanging) {
  expect_usage_error("run --lcm-url memq:// --scenario traffic-conflict",
                     "a3rig: error: --lcm-url 'memq://': memq:// delivers only inside one LCM instance");
  expect_usage_error("mcp --lcm-url memq:// --scenario traffic-conflict",
                     "a3rig: error: --lcm-url 'memq://': memq:// delivers only inside one LCM instance");
  ::setenv("LCM_DEFAULT_URL", "memq://", 1);
  expect_usage_error("run --scenario traffic-conflict --sync free",
                     "a3rig: error: LCM_DEFAULT_URL 'memq://': memq:// delivers only inside one LCM instance");
  ::unsetenv("LCM_DEFAULT_URL");
}

TEST(CliUsage, AnUnknownScenarioAndTheHelpNameEveryKindOfScenario) {
  const Outcome unknown = a3rig("run --runtime virtual --scenario no-such-place");
  EXPECT_EQ(unknown.exit_status, 2) << unknown.output;
  for (const std::string kind : {"survey-field", "gen:SEED", "alphabench:<path>", "existing file"}) {
    EXPECT_NE(unknown.output.find(kind), std::string::npos) << kind << ": " << unknown.output;
  }
  Outcome help = a3rig("run --help");
  std::istringstream words(help.output);  // wrapped at 100 columns: search its words, one space apart
  help.output.clear();
  for (std::string word; words >> word;) help.output += (help.output.empty() ? "" : " ") + word;
  EXPECT_NE(help.output.find("gen:SEED"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("traffic-conflict"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("model:<name>, a model of the paper (") , std::string::npos) << help.output;
  EXPECT_NE(help.output.find("ChatGPT-4o"), std::string::npos) << "the model names are listed: " << help.output;
}

TEST(CliUsage, AReportOfACorpusEpisodeIsWrittenHereNotIntoTheCorpus) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(::testing::TempDir()) / ("a3rig-report-" + std::to_string(::getpid()));
  fs::create_directories(root / "shared/alphabench/eval_runs/m/uav");
  fs::create_directories(root / "here");
  const fs::path episode = root / "shared/alphabench/eval_runs/m/uav/sc-0001-ep-00.json";
  std::ofstream(episode) << R"({"dialogue": [], "success": false})";
  // (a3rig() runs "a3rig ARGS": --version first, then the report from the folder "here")
  const Outcome o = a3rig("--version > /dev/null; cd " + (root / "here").string() + " && " + A3_BINARY_DIR +
                          "/a3rig report " + episode.string() + " --shared-dir " + (root / "shared").string());
  EXPECT_EQ(o.exit_status, 0) << o.output;
  EXPECT_TRUE(fs::is_regular_file(root / "here/sc-0001-ep-00.html")) << o.output;
  EXPECT_FALSE(fs::exists(episode.parent_path() / "sc-0001-ep-00.html")) << o.output;
  fs::remove_all(root);
}

TEST(CliUsage, QuietPrintsNoInfoLines) {
  const std::string out = ::testing::TempDir() + "a3rig-quiet-" + std::to_string(::getpid());
  const Outcome o = a3rig("run --runtime virtual --scenario traffic-conflict --no-lcm-log --no-plot --no-report -q --out " + out);
  EXPECT_EQ(o.exit_status, 0) << o.output;
  EXPECT_EQ(o.output.find("[info]"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("episode:"), std::string::npos) << "the closing lines stay: " << o.output;
  std::filesystem::remove_all(out);
}

TEST(CliUsage, HelpCommandPrintsACommandsLongTextsWithoutItsOptions) {
  Outcome o = a3rig("help run");
  EXPECT_EQ(o.exit_status, 0) << o.output;
  EXPECT_NE(o.output.find("Exit status: 0 the episode was written"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("A3_LLM_API_KEY"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("--scenario"), std::string::npos) << "no options: " << o.output;
  o = a3rig("help node fc");
  EXPECT_EQ(o.exit_status, 0) << o.output;
  o = a3rig("help flyfast");
  EXPECT_EQ(o.exit_status, 2) << o.output;
  EXPECT_NE(o.output.find("no command 'flyfast' (known: "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("sweep"), std::string::npos) << o.output;
}

TEST(CliUsage, TopologyPrintsTheRigsGraphAsTextAndDot) {
  Outcome o = a3rig("topology --scenario parcel-delivery");
  EXPECT_EQ(o.exit_status, 0) << o.output;
  EXPECT_NE(o.output.find("A3_FC_CMD  a3lcm.fc_command_t\n    published by  tool_server\n    subscribed by bridge"),
            std::string::npos)
      << o.output;
  o = a3rig("topology --runtime virtual --format dot");
  EXPECT_EQ(o.exit_status, 0) << o.output;
  EXPECT_EQ(o.output.rfind("digraph a3rig {", 0), 0u) << o.output;
  o = a3rig("topology --format svg");
  EXPECT_EQ(o.exit_status, 2) << o.output;
}

TEST(CliUsage, TheProgramsHelpFitsAScreenAndListsEveryCommandOnce) {
  const Outcome o = a3rig("--help");
  EXPECT_EQ(o.exit_status, 0) << o.output;
  EXPECT_LE(lines(o.output), 60) << o.output;
  std::size_t at = 0;
  for (std::size_t end = o.output.find('\n'); end != std::string::npos; at = end + 1, end = o.output.find('\n', at)) {
    std::size_t columns = 0;
    for (std::size_t i = at; i < end; ++i) columns += (static_cast<unsigned char>(o.output[i]) & 0xC0) != 0x80;
    EXPECT_LE(columns, 100u) << o.output.substr(at, end - at);
  }
  for (const std::string group : {"Fly:", "Serve:", "Evaluate:", "Tools:"}) {
    EXPECT_NE(o.output.find("\n" + group + "\n"), std::string::npos) << group << "\n" << o.output;
  }
  EXPECT_EQ(o.output.find("Other:"), std::string::npos) << "every command has its group: " << o.output;
  for (const std::string command : {"run", "mcp", "sweep", "serve-model", "score", "validate", "report", "generate",
                                    "scenario", "can", "topology", "help"}) {
    EXPECT_NE(o.output.find("\n  " + command + " "), std::string::npos) << command << "\n" << o.output;
  }
}

TEST(CliUsage, CheckArgsChecksACommandLineWithoutRunningIt) {
  const std::string out = ::testing::TempDir() + "a3rig-check-args-" + std::to_string(::getpid());
  const Outcome good = a3rig("--check-args run --scenario traffic-conflict --runtime virtual --out " + out);
  EXPECT_EQ(good.exit_status, 0) << good.output;
  EXPECT_FALSE(std::filesystem::exists(out)) << "nothing ran";
  expect_usage_error("--check-args run --no-such-flag",
                     "a3rig run: The following argument was not expected: --no-such-flag");
  expect_usage_error("--check-args run --rtf 0", "a3rig run: --rtf: must be > 0 (got 0)");
}

TEST(CliUsage, ACommandsHelpIsItsSummaryUsageAndOptionsThenAClosingSectionAllWithin100Columns) {
  const Outcome o = a3rig("run --help");
  EXPECT_EQ(o.exit_status, 0) << o.output;
  EXPECT_EQ(o.output.rfind("Fly one conversational mission on the rig", 0), 0u) << o.output;
  const std::size_t usage = o.output.find("Usage:"), exit_status = o.output.find("Exit status: 0");
  EXPECT_LT(usage, o.output.find("--scenario")) << o.output;
  EXPECT_LT(o.output.find("--scenario"), exit_status) << "exit codes close the help: " << o.output;
  std::size_t at = 0;
  for (std::size_t end = o.output.find('\n'); end != std::string::npos; at = end + 1, end = o.output.find('\n', at)) {
    std::size_t columns = 0;
    for (std::size_t i = at; i < end; ++i) columns += (static_cast<unsigned char>(o.output[i]) & 0xC0) != 0x80;
    EXPECT_LE(columns, 100u) << o.output.substr(at, end - at);
  }
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
