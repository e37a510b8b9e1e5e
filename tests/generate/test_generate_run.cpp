// A generate run (rigs/generate/generate_run.hpp) with a scripted chat: the file layout, resuming
// (valid episodes and stubs kept, invalid files replaced, another seed list refused), stopping
// early on an endpoint failure with the finished files kept, and concurrent jobs.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <map>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "rigs/generate/generate_run.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using a3::agent::llm::ChatMessage;
using a3::agent::llm::LlmCallResult;
using nlohmann::ordered_json;

class GenerateRun : public ::testing::Test {
 protected:
  void SetUp() override {
    const fs::path folder = a3::test::shared_dir() / "alphabench/eval_runs/openai/chatgpt-4o-latest/uav";
    if (!fs::exists(folder)) GTEST_SKIP() << a3::test::shared_missing_message(folder);
    for (int s : {1, 2}) {
      char name[32];
      std::snprintf(name, sizeof name, "sc-%04d-ep-00.json", s);
      std::ifstream in(folder / name);
      std::stringstream ss;
      ss << in.rdbuf();
      ordered_json episode = ordered_json::parse(ss.str());
      episode.erase("_meta");
      episodes_[s] = episode.dump();
      a3::rigs::GenerateScenario scenario;
      scenario.number = s;
      scenario.source = name;
      scenario.initial_state = episode["initial_state"];
      options_.scenarios.push_back(scenario);
    }
    dir_ = fs::temp_directory_path() / ("a3_generate_run_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    options_.output_dir = dir_ / "openai/x/uav";
    options_.model_label = "openai/x";
    options_.seeds = {42, 77};
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A chat answering the episode of the scenario the request names; scenario 2 with non-JSON
  // when `fail_scenario_2`; the endpoint down after `calls_before_down` calls.
  a3::rigs::GenerateChatFactory factory(bool fail_scenario_2 = false, int calls_before_down = 1 << 30) {
    return [this, fail_scenario_2, calls_before_down] {
      return a3::rigs::GenerateChat([this, fail_scenario_2, calls_before_down](const std::vector<ChatMessage>& m) {
        LlmCallResult r;
        if (calls_.fetch_add(1) >= calls_before_down) {
          r.error = "connection refused";
          return r;
        }
        r.ok = true;
        r.http_status = 200;
        const bool two = m.at(1).content.find("scenario_id: sc-0002") != std::string::npos;
        r.content = two && fail_scenario_2 ? "no" : episodes_.at(two ? 2 : 1);
        r.usage.total_tokens = 1000;
        return r;
      });
    };
  }
  a3::rigs::GenerateRunSummary run() { return a3::rigs::run_generate(options_, factory(), nullptr, nullptr); }

  std::map<int, std::string> episodes_;
  a3::rigs::GenerateRunOptions options_;
  fs::path dir_;
  std::atomic<int> calls_{0};
};

TEST_F(GenerateRun, WritesTheScoreLayoutAndResumesWhereItStopped) {
  auto s = run();
  EXPECT_EQ(s.planned, 4u);
  EXPECT_EQ(s.generated_valid, 4u);
  EXPECT_EQ(s.total_tokens, 4000);
  for (const char* name : {"sc-0001-ep-00.json", "sc-0001-ep-01.json", "sc-0002-ep-00.json", "sc-0002-ep-01.json"}) {
    EXPECT_TRUE(fs::exists(options_.output_dir / name)) << name;
  }
  std::ifstream in(options_.output_dir / "sc-0002-ep-01.json");
  EXPECT_EQ(ordered_json::parse(in)["_meta"]["seed"], 77);

  // Nothing left: nothing is asked.
  calls_ = 0;
  s = run();
  EXPECT_EQ(s.kept_valid, 4u);
  EXPECT_EQ(s.generated_valid, 0u);
  EXPECT_EQ(calls_.load(), 0);

  // A missing file and a broken one are generated again; a stale temporary file is removed.
  fs::remove(options_.output_dir / "sc-0001-ep-01.json");
  std::ofstream(options_.output_dir / "sc-0002-ep-00.json") << "{\"initial_state\": ";
  std::ofstream(options_.output_dir / "sc-0002-ep-01.json.999-0.tmp") << "half";
  s = run();
  EXPECT_EQ(s.kept_valid, 2u);
  EXPECT_EQ(s.replaced_invalid, 1u);
  EXPECT_EQ(s.generated_valid, 2u);
  EXPECT_FALSE(fs::exists(options_.output_dir / "sc-0002-ep-01.json.999-0.tmp"));

  // Another seed list would mix seeds under the same names: refused before anything is asked.
  options_.seeds = {77, 42};
  calls_ = 0;
  try {
    run();
    FAIL() << "another seed list was not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sc-0001-ep-00.json is an episode of seed 42, but --seeds puts seed 77"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(calls_.load(), 0);
}

TEST_F(GenerateRun, StubsAreKeptUnlessRetriedAndAnEndpointFailureStopsTheRun) {
  auto s = a3::rigs::run_generate(options_, factory(true), nullptr, nullptr);
  EXPECT_EQ(s.generated_valid, 2u);
  EXPECT_EQ(s.generated_stubs, 2u);
  EXPECT_EQ(calls_.load(), 2 + 2 * 3);
  s = a3::rigs::run_generate(options_, factory(), nullptr, nullptr);
  EXPECT_EQ(s.kept_stubs, 2u);
  EXPECT_EQ(s.generated_valid + s.generated_stubs, 0u);
  options_.retry_failed = true;
  s = a3::rigs::run_generate(options_, factory(), nullptr, nullptr);
  EXPECT_EQ(s.generated_valid, 2u);

  fs::remove_all(options_.output_dir);
  calls_ = 0;
  s = a3::rigs::run_generate(options_, factory(false, 1), nullptr, nullptr);
  EXPECT_EQ(s.generated_valid, 1u);
  EXPECT_EQ(s.not_generated, 3u);
  EXPECT_NE(s.stop_error.find("connection refused"), std::string::npos) << s.stop_error;
  EXPECT_TRUE(fs::exists(options_.output_dir / "sc-0001-ep-00.json"));
  EXPECT_FALSE(fs::exists(options_.output_dir / "sc-0001-ep-01.json"));
}

TEST_F(GenerateRun, JobsRunConcurrentlyAndReportProgressWithAnEta) {
  options_.jobs = 3;
  std::vector<a3::rigs::GenerateProgress> reports;
  const auto s = a3::rigs::run_generate(
      options_, factory(), [&](const a3::rigs::GenerateProgress& p) { reports.push_back(p); }, nullptr);
  EXPECT_EQ(s.generated_valid, 4u);
  ASSERT_EQ(reports.size(), 4u);
  for (std::size_t i = 0; i < reports.size(); ++i) {
    EXPECT_EQ(reports[i].done, i + 1);
    EXPECT_EQ(reports[i].to_do, 4u);
    EXPECT_GE(reports[i].eta_s, 0.0);
  }
  EXPECT_EQ(reports.back().eta_s, 0.0);
  options_.jobs = 0;
  EXPECT_THROW(run(), std::invalid_argument);
  options_.jobs = 1;
  options_.seeds = {42, 42};
  EXPECT_THROW(run(), std::invalid_argument);
}

}  // namespace
