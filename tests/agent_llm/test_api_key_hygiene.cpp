// The API key never leaves the environment: the real `a3rig run --agent llm` program flies a
// mission against a model server on loopback that requires the key, with A3_LLM_API_KEY set to a
// distinctive secret. The secret must appear in none of: the program's stdout and stderr, any
// file it wrote (episode.json, the LCM log, the plot and its data), its command line
// (/proc/PID/cmdline) and the process listing (`ps -eo args`) taken while it runs. With a wrong
// key, the 401 is reported (naming the problem) without either key by the endpoint check before
// take-off, which stops the run (exit 7, endpoint_failed).
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "agent/model_server/model_server.hpp"
#include "agent/model_server/scripted_responder.hpp"
#include "tests/test_support.hpp"

extern char** environ;

namespace a3 {
namespace {

namespace fs = std::filesystem;
namespace ms = agent::model_server;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string command_output(const char* command) {
  std::string out;
  FILE* pipe = ::popen(command, "r");
  if (pipe == nullptr) return out;
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  ::pclose(pipe);
  return out;
}

struct Observed {
  int exit_status = -1;
  std::string output;                 // stdout and stderr
  std::vector<std::string> listings;  // `ps -eo args` while it ran
  std::vector<std::string> cmdlines;  // /proc/PID/cmdline while it ran
};

// Runs `args` with the environment of this process minus every LLM key variable, plus `extra`;
// watches its command line and the process listing until it exits.
Observed run_watched(const std::vector<std::string>& args, const std::vector<std::string>& extra,
                     const fs::path& output_file) {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string v = *e;
    if (v.rfind("A3_LLM_", 0) == 0 || v.rfind("OPENAI_API_KEY=", 0) == 0) continue;
    env.push_back(v);
  }
  for (const auto& v : extra) env.push_back(v);
  std::vector<char*> argv, envp;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  for (const auto& v : env) envp.push_back(const_cast<char*>(v.c_str()));
  envp.push_back(nullptr);

  Observed o;
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd < 0) ::_exit(126);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  if (pid < 0) return o;
  const std::string proc_cmdline = "/proc/" + std::to_string(pid) + "/cmdline";
  int status = 0;
  while (true) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    std::string cmdline = read_file(proc_cmdline);
    if (!cmdline.empty()) o.cmdlines.push_back(std::move(cmdline));
    o.listings.push_back(command_output("ps -ww -eo args 2>/dev/null"));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  o.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  o.output = read_file(output_file);
  return o;
}

std::string distinctive(const std::string& prefix) {
  std::random_device rd;
  char text[64];
  std::snprintf(text, sizeof text, "%s-%08x%08x", prefix.c_str(), rd(), rd());
  return text;
}

struct KeyedServer {
  ms::ModelServer server;
  explicit KeyedServer(const std::string& key_env)
      : server(std::make_unique<ms::ScriptedResponder>(), options(key_env), [](const std::string&) {}) {
    server.start();
  }
  ~KeyedServer() { server.stop(); }
  static ms::ModelServerOptions options(const std::string& key_env) {
    ms::ModelServerOptions o;
    o.port = 0;
    o.latency = "0";
    o.quiet = true;
    o.require_key_env = key_env;
    return o;
  }
};

struct Fixture : ::testing::Test {
  const std::string secret = distinctive("sk-a3rig-hygiene");
  const fs::path out = fs::temp_directory_path() / ("a3rig-key-hygiene-" + std::to_string(::getpid()));
  std::unique_ptr<KeyedServer> server;

  void SetUp() override {
    ::setenv("A3_TEST_REQUIRED_KEY", secret.c_str(), 1);
    server = std::make_unique<KeyedServer>("A3_TEST_REQUIRED_KEY");
    fs::remove_all(out);
    fs::create_directories(out);
  }
  void TearDown() override {
    server.reset();
    ::unsetenv("A3_TEST_REQUIRED_KEY");
    fs::remove_all(out);
  }
  Observed run(const std::string& key, const std::string& tag) {
    const std::vector<std::string> args = {std::string(A3_BINARY_DIR) + "/a3rig", "run", "--agent", "llm",
                                           "--runtime", "virtual", "--scenario", "survey-field",
                                           "--llm-base-url", server->server.base_url(), "--llm-model",
                                           "scripted", "--out", (out / tag).string()};
    return run_watched(args, {"A3_LLM_API_KEY=" + key}, out / (tag + ".output"));
  }
  // Every file the run wrote, that contains `needle`.
  std::vector<std::string> files_containing(const fs::path& dir, const std::string& needle) {
    std::vector<std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      if (entry.is_regular_file() && read_file(entry.path()).find(needle) != std::string::npos) {
        found.push_back(entry.path().string());
      }
    }
    return found;
  }
};

TEST_F(Fixture, TheKeyAppearsInNoOutputFileOrProcessListing) {
  const Observed o = run(secret, "right");
  ASSERT_EQ(o.exit_status, 0) << o.output;
  EXPECT_NE(o.output.find("success: true"), std::string::npos) << o.output;
  EXPECT_EQ(server->server.stats().unauthorized, 0u);
  EXPECT_GE(server->server.stats().answered, 4u) << "the key was sent and accepted";

  EXPECT_EQ(o.output.find(secret), std::string::npos) << "stdout/stderr";
  const fs::path dir = out / "right";
  for (const char* f : {"episode.json", "episode.lcmlog", "trajectory.png"}) EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_EQ(files_containing(dir, secret), std::vector<std::string>{});
  ASSERT_FALSE(o.listings.empty()) << "the run ended before it could be watched";
  bool listed = false;
  for (const auto& l : o.listings) {
    EXPECT_EQ(l.find(secret), std::string::npos) << "ps -eo args";
    listed |= l.find("--llm-model scripted --out " + dir.string()) != std::string::npos;
  }
  EXPECT_TRUE(listed) << "the run's command line was never seen in the process listing";
  for (const auto& c : o.cmdlines) EXPECT_EQ(c.find(secret), std::string::npos) << "/proc/PID/cmdline";
  // The watched command line is the run's (the first reads may precede the exec).
  bool seen_run = false;
  for (const auto& c : o.cmdlines) seen_run |= c.find("--agent") != std::string::npos;
  EXPECT_TRUE(seen_run) << "the run's /proc/PID/cmdline was never read";
}

// A wrong key is the endpoint's refusal (401): the check before take-off stops the run (exit 7,
// endpoint_failed) with the server's reason and without either key, and nothing flies.
TEST_F(Fixture, AWrongKeyStopsTheRunBeforeTakeOffAndIsReportedWithoutTheKey) {
  const std::string wrong = distinctive("sk-a3rig-wrong");
  const Observed o = run(wrong, "wrong");
  ASSERT_EQ(o.exit_status, 7) << o.output;
  EXPECT_NE(o.output.find("401"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("API key"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("status endpoint_failed"), std::string::npos) << o.output;
  for (const auto& k : {secret, wrong}) {
    EXPECT_EQ(o.output.find(k), std::string::npos);
    if (fs::exists(out / "wrong")) {
      EXPECT_EQ(files_containing(out / "wrong", k), std::vector<std::string>{});
    }
    for (const auto& l : o.listings) EXPECT_EQ(l.find(k), std::string::npos);
  }
  EXPECT_GE(server->server.stats().unauthorized, 1u);
  EXPECT_EQ(server->server.stats().answered, 0u);
  EXPECT_FALSE(fs::exists(out / "wrong" / "episode.json")) << "nothing flew";
}

}  // namespace
}  // namespace a3
