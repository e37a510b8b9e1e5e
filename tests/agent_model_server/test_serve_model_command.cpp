// `a3rig serve-model` as a process: it announces its port in --ready-file, answers the LLM
// client, stops with exit status 0 on SIGTERM with a summary, and refuses bad usage with 2.
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
#include "tests/integration/spawned_process.hpp"

namespace {

namespace fs = std::filesystem;

std::string a3rig() { return std::string(A3_BINARY_DIR) + "/a3rig"; }

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("a3_serve_model_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

using a3::test::read_file;
using a3::test::spawn;
using a3::test::wait_exit;

TEST(ServeModelCommand, ServesTheClientAndStopsCleanlyOnSigterm) {
  if (!fs::exists(a3rig())) GTEST_SKIP() << a3rig() << " is not built (build the a3rig target)";
  const fs::path dir = temp_dir();
  const fs::path ready = dir / "port";
  const fs::path reply = dir / "reply.json";
  std::ofstream(reply) << R"({"intent":"survey the field","actions":[]})";
  const pid_t pid = spawn({a3rig(), "serve-model", "--responder", "reply-file", "--reply-file", reply.string(),
                           "--port", "0", "--ready-file", ready.string(), "--latency", "fixed:0.05"},
                          dir / "out.txt", dir / "err.txt");
  ASSERT_GT(pid, 0);
  int port = 0;
  for (int i = 0; i < 1000 && port == 0; ++i) {  // up to 20 s on a loaded machine
    if (fs::exists(ready)) port = std::atoi(read_file(ready).c_str());
    if (port == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GT(port, 0) << "no port in " << ready << "; stderr: " << read_file(dir / "err.txt");

  a3::agent::llm::LlmEndpoint e;
  e.base_url = "http://127.0.0.1:" + std::to_string(port) + "/v1";
  e.model = "local/reply";
  a3::agent::llm::LlmClient client(e);
  const auto r = client.chat({{"user", "Survey the field."}});
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.content, R"({"intent":"survey the field","actions":[]})");
  EXPECT_GE(r.wall_time_s, 0.05);

  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  EXPECT_EQ(wait_exit(pid, 30.0), 0) << read_file(dir / "err.txt");
  const std::string out = read_file(dir / "out.txt");
  EXPECT_NE(out.find("serving reply-file on http://127.0.0.1:" + std::to_string(port) + "/v1 (latency fixed:0.05"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("1 requests, 1 answered"), std::string::npos) << out;
  EXPECT_NE(read_file(dir / "err.txt").find("POST /v1/chat/completions 200 model=local/reply"), std::string::npos);
  EXPECT_FALSE(fs::exists(ready));  // removed on stop
  fs::remove_all(dir);
}

TEST(ServeModelCommand, BadUsageExitsWith2AndSaysWhy) {
  if (!fs::exists(a3rig())) GTEST_SKIP() << a3rig() << " is not built (build the a3rig target)";
  const fs::path dir = temp_dir();
  struct Case {
    std::vector<std::string> args;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {{"--responder", "reply-file", "--reply-text", "x", "--latency", "sometimes"}, "latency 'sometimes'"},
      {{"--responder", "reply-file"}, "no reply"},
      {{"--responder", "reply-file", "--reply-file", "/nonexistent/r.json"}, "/nonexistent/r.json"},
      {{"--responder", "reply-file", "--reply-text", "x", "--require-key-env", "A3_UNSET_KEY_VARIABLE_X"},
       "A3_UNSET_KEY_VARIABLE_X is not set"},
      {{"--responder", "oracle"}, "oracle"},  // CLI11's own usage error: its exit code
  };
  ::unsetenv("A3_UNSET_KEY_VARIABLE_X");
  for (const auto& c : cases) {
    std::vector<std::string> args = {a3rig(), "serve-model", "--port", "0"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const pid_t pid = spawn(args, dir / "out.txt", dir / "err.txt");
    ASSERT_GT(pid, 0);
    const int status = wait_exit(pid, 30.0);
    const std::string err = read_file(dir / "err.txt") + read_file(dir / "out.txt");
    if (c.args[1] == "oracle") {
      EXPECT_GT(status, 0) << err;
    } else {
      EXPECT_EQ(status, 2) << c.expected << ": " << err;
    }
    EXPECT_NE(err.find(c.expected), std::string::npos) << err;
  }
  fs::remove_all(dir);
}

TEST(ServeModelCommand, HelpNamesTheOpenAiFeaturesItHonours) {
  if (!fs::exists(a3rig())) GTEST_SKIP() << a3rig() << " is not built (build the a3rig target)";
  const fs::path dir = temp_dir();
  const pid_t pid = spawn({a3rig(), "serve-model", "--help"}, dir / "out.txt", dir / "err.txt");
  ASSERT_GT(pid, 0);
  EXPECT_EQ(wait_exit(pid, 30.0), 0);
  // The help is wrapped at 100 columns: its words, one space apart, are what is searched.
  std::string help;
  std::istringstream words(read_file(dir / "out.txt"));
  for (std::string word; words >> word;) help += (help.empty() ? "" : " ") + word;
  for (const char* feature : {"GET /v1/models/{id}", "tool_choice", "response_format", "stream: true", "n (1-8)",
                              "a 400 naming the field", "415", "include_usage", "half the latency"}) {
    EXPECT_NE(help.find(feature), std::string::npos) << feature;
  }
  fs::remove_all(dir);
}

}  // namespace
