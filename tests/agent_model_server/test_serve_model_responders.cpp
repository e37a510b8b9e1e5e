// `a3rig serve-model --responder corpus` and `--responder scripted` as processes: the corpus one
// answers a generate request with the recorded episode and usage, the scripted one answers
// (here: a request without an agent context, with its generic text), and a bad --corpus
// is a usage error naming the folder.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "agent/llm/llm_client.hpp"
#include "tests/test_support.hpp"
#include "tests/integration/spawned_process.hpp"

namespace {

namespace fs = std::filesystem;

std::string a3rig() { return std::string(A3_BINARY_DIR) + "/a3rig"; }

using a3::test::read_file;
using a3::test::spawn;
using a3::test::wait_exit;

// Starts serve-model with `args`; returns the port (0 when it did not come up).
int start(const std::vector<std::string>& args, const fs::path& dir, pid_t& pid) {
  const fs::path ready = dir / "port";
  std::vector<std::string> argv = {a3rig(), "serve-model", "--port", "0", "--ready-file", ready.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  pid = spawn(argv, dir / "out.txt", dir / "err.txt");
  int port = 0;
  for (int i = 0; i < 1000 && pid > 0 && port == 0; ++i) {
    if (fs::exists(ready)) port = std::atoi(read_file(ready).c_str());
    if (port == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return port;
}

a3::agent::llm::LlmClient client_for(int port) {
  a3::agent::llm::LlmEndpoint e;
  e.base_url = "http://127.0.0.1:" + std::to_string(port) + "/v1";
  e.model = "openai/chatgpt-4o-latest";
  e.max_retries = 0;
  return a3::agent::llm::LlmClient(e);
}

TEST(ServeModelResponders, CorpusAnswersTheRecordedEpisodeAndScriptedAnswersAgentTurns) {
  if (!fs::exists(a3rig())) GTEST_SKIP() << a3rig() << " is not built (build the a3rig target)";
  A3_REQUIRE_SHARED(folder, "alphabench/eval_runs/openai/chatgpt-4o-latest/uav");
  const fs::path dir = fs::temp_directory_path() / ("a3_serve_responders_" + std::to_string(::getpid()));
  fs::create_directories(dir);

  pid_t pid = -1;
  int port = start({"--responder", "corpus", "--corpus", folder.string(), "--time-scale", "0"}, dir, pid);
  ASSERT_GT(port, 0) << read_file(dir / "err.txt");
  {
    auto client = client_for(port);
    const auto r = client.chat(std::vector<a3::agent::llm::ChatMessage>{{"user", "scenario_id: sc-0005\nepisode_seed: 42\nattempt: 1 of 3\n"}});
    ASSERT_TRUE(r.ok) << r.error;
    std::ifstream in(folder / "sc-0005-ep-00.json");
    nlohmann::json recorded = nlohmann::json::parse(in);
    EXPECT_EQ(r.usage.total_tokens, recorded["_meta"]["usage"]["total_tokens"].get<int64_t>());
    recorded.erase("_meta");
    EXPECT_EQ(nlohmann::json::parse(r.content), recorded);
  }
  ::kill(pid, SIGTERM);
  EXPECT_EQ(wait_exit(pid, 30.0), 0);
  EXPECT_NE(read_file(dir / "out.txt").find("serving corpus on"), std::string::npos) << read_file(dir / "out.txt");

  port = start({"--responder", "scripted"}, dir, pid);
  ASSERT_GT(port, 0) << read_file(dir / "err.txt");
  {
    auto client = client_for(port);
    const auto r = client.chat(std::vector<a3::agent::llm::ChatMessage>{{"user", "Fly somewhere."}});
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_NE(r.content.find("scripted responder"), std::string::npos) << r.content;
  }
  ::kill(pid, SIGTERM);
  EXPECT_EQ(wait_exit(pid, 30.0), 0);
  EXPECT_NE(read_file(dir / "out.txt").find("serving scripted on"), std::string::npos) << read_file(dir / "out.txt");
  fs::remove_all(dir);
}

TEST(ServeModelResponders, BadCorpusUsageExitsWith2AndSaysWhy) {
  if (!fs::exists(a3rig())) GTEST_SKIP() << a3rig() << " is not built (build the a3rig target)";
  const fs::path dir = fs::temp_directory_path() / ("a3_serve_responders_bad_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  struct Case {
    std::vector<std::string> args;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {{"--responder", "corpus", "--corpus", "/nonexistent/a3/uav"}, "--corpus /nonexistent/a3/uav: not a folder"},
      {{"--responder", "corpus"}, "give --corpus DIR"},
      {{"--responder", "reply-file", "--reply-text", "x", "--corpus", dir.string()},
       "--corpus is an option of --responder corpus"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {a3rig(), "serve-model", "--port", "0"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const pid_t pid = spawn(args, dir / "out.txt", dir / "err.txt");
    ASSERT_GT(pid, 0);
    EXPECT_EQ(wait_exit(pid, 30.0), 2) << c.expected;
    const std::string err = read_file(dir / "err.txt");
    EXPECT_NE(err.find(c.expected), std::string::npos) << err;
  }
  fs::remove_all(dir);
}

}  // namespace
