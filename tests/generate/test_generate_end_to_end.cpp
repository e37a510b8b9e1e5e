// The end-to-end test: `a3rig serve-model --responder corpus` replays one model folder of
// the public α³-Bench release on loopback, `a3rig generate` writes that model's episodes against
// it (seed 42, which the corpus's ep-00 files are), and `a3rig score` on the output gives the
// same leaderboard row as on the recorded folder. ChatGPT-4o runs at the recorded latency (all
// 50 episodes at once, ~16 s): every column equal, the timing ones to within the loopback's
// overhead. Gemini-3-Pro-Preview (failure stubs, retries) and GPT-5.1-Chat (retries) run with
// the latency scaled to 0: every column but the timing ones equal.
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

#include <nlohmann/json.hpp>

#include "tests/test_support.hpp"
#include "tests/integration/spawned_process.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string a3rig() { return std::string(A3_BINARY_DIR) + "/a3rig"; }

using a3::test::read_file;
using a3::test::spawn;
using a3::test::wait_exit;

// Runs a3rig to completion; returns its exit status, stdout in `out` and stderr in `err`.
int run(const std::vector<std::string>& args, const fs::path& dir, std::string& out, std::string& err,
        double timeout_s = 120.0) {
  std::vector<std::string> argv = {a3rig()};
  argv.insert(argv.end(), args.begin(), args.end());
  const pid_t pid = spawn(argv, dir / "run.out", dir / "run.err");
  if (pid <= 0) return -1;
  const int status = wait_exit(pid, timeout_s);
  out = read_file(dir / "run.out");
  err = read_file(dir / "run.err");
  return status;
}

// The corpus server for one model folder, stopped when the test ends.
class CorpusServer {
 public:
  CorpusServer(const fs::path& folder, double time_scale, const fs::path& dir) : dir_(dir) {
    const fs::path ready = dir / "port";
    pid_ = spawn({a3rig(), "serve-model", "--responder", "corpus", "--corpus", folder.string(), "--port", "0",
                  "--ready-file", ready.string(), "--time-scale", std::to_string(time_scale), "--threads", "64",
                  "--quiet"},
                 dir / "server.out", dir / "server.err");
    for (int i = 0; i < 1500 && pid_ > 0 && port_ == 0; ++i) {  // up to 30 s on a loaded machine
      if (fs::exists(ready)) port_ = std::atoi(read_file(ready).c_str());
      if (port_ == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  ~CorpusServer() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      wait_exit(pid_, 30.0);
    }
  }
  int port() const { return port_; }
  std::string errors() const { return read_file(dir_ / "server.err"); }
  std::string base_url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1"; }

 private:
  fs::path dir_;
  pid_t pid_ = -1;
  int port_ = 0;
};

json score(const fs::path& root, const fs::path& dir) {
  std::string out, err;
  const int status = run({"score", "--format", "json", "--quiet", root.string()}, dir, out, err);
  EXPECT_EQ(status, 0) << err;
  const json rows = json::parse(out, nullptr, false);
  if (rows.is_discarded() || !rows.is_array() || rows.size() != 1) {
    ADD_FAILURE() << "a3rig score " << root << " printed no single-row JSON leaderboard: " << out << err;
    return json::object();
  }
  return rows[0];
}

struct Case {
  std::string model;   // provider/model under alphabench/eval_runs
  double time_scale;   // of the recorded latency
  int jobs;            // episodes at once
};

// Generates the model's episodes from the corpus server and scores them and the recorded folder.
void generate_and_compare(const Case& c) {
  if (!fs::exists(a3rig())) GTEST_SKIP() << a3rig() << " is not built (build the a3rig target)";
  A3_REQUIRE_SHARED(folder, "alphabench/eval_runs/" + c.model + "/uav");
  const fs::path dir = fs::temp_directory_path() /
                       ("a3_generate_e2e_" + std::to_string(::getpid()) + "_" + fs::path(c.model).filename().string());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out_root = dir / "runs";
  {
    CorpusServer server(folder, c.time_scale, dir);
    ASSERT_GT(server.port(), 0) << "serve-model did not start: " << server.errors();
    std::string out, err;
    const auto t0 = std::chrono::steady_clock::now();
    const int status = run({"generate", "--scenarios", folder.string(), "--seeds", "42", "--out", out_root.string(),
                            "--llm-base-url", server.base_url(), "--llm-model", c.model, "--jobs",
                            std::to_string(c.jobs)},
                           dir, out, err, 240.0);
    const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(status, 0) << err << "\nserver: " << server.errors();
    EXPECT_EQ(out, (out_root / c.model / "uav").string() + "\n");
    EXPECT_NE(err.find("[50/50] "), std::string::npos) << err;
    std::printf("[ figure   ] %s: generate took %.1f s at time scale %g with %d jobs\n", c.model.c_str(), took_s,
                c.time_scale, c.jobs);

    // Resuming a finished run asks for nothing.
    const int again = run({"generate", "--scenarios", folder.string(), "--seeds", "42", "--out",
                           out_root.string(), "--llm-base-url", server.base_url(), "--llm-model", c.model},
                          dir, out, err);
    EXPECT_EQ(again, 0) << err;
    EXPECT_NE(err.find("50 kept"), std::string::npos) << err;
    EXPECT_NE(err.find("0 generated"), std::string::npos) << err;
  }
  for (int s = 0; s < 50; ++s) {
    char name[32];
    std::snprintf(name, sizeof name, "sc-%04d-ep-00.json", s);
    EXPECT_TRUE(fs::exists(out_root / c.model / "uav" / name)) << name;
  }

  const json generated = score(out_root, dir);
  const json recorded = score(folder, dir);
  ASSERT_FALSE(generated.empty());
  ASSERT_FALSE(recorded.empty());
  ASSERT_EQ(generated.size(), recorded.size());
  for (auto it = recorded.begin(); it != recorded.end(); ++it) {
    const std::string& column = it.key();
    ASSERT_TRUE(generated.contains(column)) << column;
    if (column == "mean_gen_time_s" || column == "alpha3_per_second") continue;
    EXPECT_EQ(generated[column], *it) << column;
  }
  const double recorded_time_s = recorded["mean_gen_time_s"].get<double>();
  const double generated_time_s = generated["mean_gen_time_s"].get<double>();
  // The server waits the scaled recorded latency; the client adds only loopback and parsing.
  EXPECT_GE(generated_time_s, c.time_scale * recorded_time_s - 1e-6);
  EXPECT_LE(generated_time_s, c.time_scale * recorded_time_s + 0.5);
  if (c.time_scale == 1.0) {
    EXPECT_NEAR(generated["alpha3_per_second"].get<double>(), recorded["alpha3_per_second"].get<double>(),
                0.05 * recorded["alpha3_per_second"].get<double>());
  }
  std::printf("[ figure   ] %s: mean_gen_time_s %.5f generated, %.5f recorded\n", c.model.c_str(), generated_time_s,
              recorded_time_s);
  fs::remove_all(dir);
}

TEST(GenerateEndToEnd, ChatGpt4oAtRecordedLatencyGivesTheRecordedLeaderboardRow) {
  generate_and_compare({"openai/chatgpt-4o-latest", 1.0, 50});
}

TEST(GenerateEndToEnd, GeminiStubsAndRetriesGiveTheRecordedLeaderboardRow) {
  generate_and_compare({"google/gemini-3-pro-preview", 0.0, 8});
}

TEST(GenerateEndToEnd, Gpt51RetriesGiveTheRecordedLeaderboardRow) {
  generate_and_compare({"openai/gpt-5.1-chat", 0.0, 8});
}

TEST(GenerateEndToEnd, AnInterruptedRunContinuesWhereItStopped) {
  if (!fs::exists(a3rig())) GTEST_SKIP() << a3rig() << " is not built (build the a3rig target)";
  A3_REQUIRE_SHARED(folder, "alphabench/eval_runs/openai/chatgpt-4o-latest/uav");
  const fs::path dir = fs::temp_directory_path() / ("a3_generate_interrupt_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out_root = dir / "runs";
  const fs::path episodes = out_root / "openai/chatgpt-4o-latest/uav";
  auto count_files = [&](const std::string& suffix) {
    std::size_t n = 0;
    if (!fs::exists(episodes)) return n;
    for (const auto& e : fs::directory_iterator(episodes)) {
      const std::string name = e.path().filename().string();
      n += name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
    }
    return n;
  };
  {
    CorpusServer server(folder, 0.005, dir);  // ~0.05 s per episode
    ASSERT_GT(server.port(), 0) << server.errors();
    const std::vector<std::string> args = {a3rig(), "generate", "--scenarios", folder.string(), "--seeds", "42",
                                           "--out", out_root.string(), "--llm-base-url", server.base_url(),
                                           "--llm-model", "openai/chatgpt-4o-latest"};
    const pid_t pid = spawn(args, dir / "gen.out", dir / "gen.err");
    ASSERT_GT(pid, 0);
    for (int i = 0; i < 1500 && count_files(".json") < 3; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_EQ(::kill(pid, SIGINT), 0);
    EXPECT_EQ(wait_exit(pid, 60.0), 3) << read_file(dir / "gen.err");
    const std::size_t written = count_files(".json");
    EXPECT_GE(written, 3u);
    EXPECT_LT(written, 50u) << "the run was not interrupted";
    EXPECT_EQ(count_files(".tmp"), 0u);
    EXPECT_NE(read_file(dir / "gen.err").find("run the same command again to continue"), std::string::npos);

    std::string out, err;
    ASSERT_EQ(run(std::vector<std::string>(args.begin() + 1, args.end()), dir, out, err), 0) << err;
    EXPECT_NE(err.find(std::to_string(written) + " kept (" + std::to_string(written) + " valid"), std::string::npos)
        << err;
    EXPECT_NE(err.find(std::to_string(50 - written) + " generated"), std::string::npos) << err;
  }
  EXPECT_EQ(count_files(".json"), 50u);
  json generated = score(out_root, dir);
  json recorded = score(folder, dir);
  for (const char* column : {"mean", "n", "pillars", "mean_total_tokens", "total_attempt_calls", "alpha3_rel"}) {
    EXPECT_EQ(generated[column], recorded[column]) << column;
  }
  fs::remove_all(dir);
}

TEST(GenerateEndToEnd, BadUsageExitsWith2AndSaysWhy) {
  if (!fs::exists(a3rig())) GTEST_SKIP() << a3rig() << " is not built (build the a3rig target)";
  const fs::path dir = fs::temp_directory_path() / ("a3_generate_usage_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  struct Usage {
    std::vector<std::string> args;
    std::string expected;
  };
  const std::vector<Usage> cases = {
      {{"--scenarios", "/nonexistent/a3/scenarios", "--out", dir.string(), "--llm-base-url",
        "http://127.0.0.1:9/v1", "--llm-model", "m/x"},
       "--scenarios /nonexistent/a3/scenarios: not a folder, a file, nor a built-in scenario"},
      {{"--scenarios", dir.string(), "--out", dir.string(), "--llm-base-url", "http://127.0.0.1:9/v1",
        "--llm-model", "m/x"},
       "no sc-XXXX-ep-YY.json file in this folder"},
      {{"--scenarios", "nfz-detour", "--out", dir.string(), "--llm-base-url", "http://127.0.0.1:9/v1", "--llm-model",
        "m/x", "--label", "a/b/c"},
       "--label a/b/c: must be PROVIDER/MODEL"},
      {{"--scenarios", "nfz-detour", "--out", dir.string(), "--llm-base-url", "http://127.0.0.1:9/v1", "--llm-model",
        "m/x", "--seeds", "42,42"},
       "a seed is given twice"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {"generate"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    std::string out, err;
    EXPECT_EQ(run(args, dir, out, err), 2) << err;
    EXPECT_NE(err.find(c.expected), std::string::npos) << err;
  }
  // An endpoint nobody listens on: exit 1, nothing written, and how to continue.
  std::string out, err;
  EXPECT_EQ(run({"generate", "--scenarios", "nfz-detour", "--seeds", "42", "--out", (dir / "runs").string(),
                 "--llm-base-url", "http://127.0.0.1:9/v1", "--llm-model", "m/x", "--retries", "0"},
                dir, out, err, 60.0),
            1)
      << err;
  EXPECT_NE(err.find("run the same command again to continue"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "runs/m/x/uav/sc-0000-ep-00.json"));
  fs::remove_all(dir);
}

}  // namespace
