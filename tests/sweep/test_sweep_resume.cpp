// The sweep's scheduling with a test runner that writes episode files without flying: a second
// run skips complete cells and runs again exactly the incomplete ones, failures and a stop are
// recorded per cell, shards write their own results files, and no more than --jobs cells run
// at once. Plus the progress line.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "rigs/sweep/sweep_report.hpp"
#include "rigs/sweep/sweep_runner.hpp"

namespace a3::rigs::sweep {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("a3-sweep-resume-" + std::to_string(::getpid()) + "-" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::remove_all(path); }
  ~TempDir() { fs::remove_all(path); }
};

// Writes what `a3rig run` would (the fields a completeness check reads), or fails on request.
class FakeRunner final : public CellRunner {
 public:
  std::set<std::size_t> fail_cells;  // grid indices that write nothing and report a failure
  std::map<std::size_t, int> violate_times;  // grid index -> how many runs break the real-time contract
  std::chrono::milliseconds run_time{0};

  CellRunOutcome run(const SweepCell& cell, const fs::path& dir, const std::atomic<bool>& stop) override {
    {
      std::lock_guard lock(mutex_);
      ran_.push_back(cell.index);
      max_running_ = std::max(max_running_, ++running_);
    }
    std::this_thread::sleep_for(run_time);
    {
      std::lock_guard lock(mutex_);
      --running_;
    }
    if (fail_cells.count(cell.index)) return {false, "a3rig run exited with status 2"};
    fs::create_directories(dir);
    std::string status = stop.load() ? "interrupted" : "completed";
    if (violate_times[cell.index] > 0) {
      --violate_times[cell.index];
      status = "realtime_violated: achieved real-time factor 1.2 below 0.5 x the requested 8";
    }
    const nlohmann::json episode = {
        {"success", cell.seed % 2 == 1},
        {"_rig",
         {{"status", status}, {"agent", cell.agent}, {"think_time", cell.think_time},
          {"seed", cell.seed}, {"mission_time_s", 100.0}, {"wall_time_s", 1.0}}}};
    std::ofstream(dir / "episode.json") << episode.dump();
    return {true, ""};
  }
  std::vector<std::size_t> ran() {
    std::lock_guard lock(mutex_);
    auto out = ran_;
    std::sort(out.begin(), out.end());
    ran_.clear();
    return out;
  }
  int max_running() const { return max_running_; }

 private:
  std::mutex mutex_;
  std::vector<std::size_t> ran_;
  int running_ = 0;
  int max_running_ = 0;
};

std::vector<SweepCell> small_grid() {
  return expand_grid(make_axes("survey-field,traffic-conflict", "scripted", "0,30", "eMBB,URLLC", "1,2"));
}

std::vector<std::size_t> all_indices(std::size_t n) {
  std::vector<std::size_t> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = i;
  return out;
}

TEST(SweepResume, ASecondRunSkipsCompleteCellsAndRerunsIncompleteOnes) {
  TempDir dir;
  const auto grid = small_grid();
  FakeRunner runner;
  SweepRunOptions options;
  options.out_dir = dir.path;
  options.jobs = 2;
  const std::atomic<bool> no_stop{false};

  const SweepRunSummary first = run_sweep(grid, options, runner, {}, no_stop);
  EXPECT_EQ(runner.ran(), all_indices(grid.size()));
  EXPECT_EQ(first.counts.ran, grid.size());
  EXPECT_EQ(first.counts.skipped, 0u);
  EXPECT_EQ(read_results_csv(dir.path / "results.csv").size(), grid.size());

  const SweepRunSummary second = run_sweep(grid, options, runner, {}, no_stop);
  EXPECT_TRUE(runner.ran().empty());
  EXPECT_EQ(second.counts.skipped, grid.size());
  EXPECT_EQ(read_results_csv(dir.path / "results.csv").size(), grid.size());

  // Three ways to be incomplete: half-written, interrupted, and another cell's episode.
  std::ofstream(cell_dir(dir.path, grid[3]) / "episode.json", std::ios::trunc) << "{\"success\": tr";
  {
    std::ifstream in(cell_dir(dir.path, grid[5]) / "episode.json");
    nlohmann::json e = nlohmann::json::parse(in);
    e["_rig"]["status"] = "interrupted";
    std::ofstream(cell_dir(dir.path, grid[5]) / "episode.json", std::ios::trunc) << e.dump();
  }
  fs::copy_file(cell_dir(dir.path, grid[0]) / "episode.json", cell_dir(dir.path, grid[9]) / "episode.json",
                fs::copy_options::overwrite_existing);
  const SweepRunSummary third = run_sweep(grid, options, runner, {}, no_stop);
  EXPECT_EQ(third.counts.to_run, 3u);
  EXPECT_EQ(runner.ran(), (std::vector<std::size_t>{3, 5, 9}));
  EXPECT_EQ(third.counts.ran, 3u);
  EXPECT_EQ(third.counts.skipped, grid.size() - 3);

  options.rerun_complete = true;
  run_sweep(grid, options, runner, {}, no_stop);
  EXPECT_EQ(runner.ran(), all_indices(grid.size()));
}

TEST(SweepResume, FailedCellsAreRecordedAndRunAgainNextTime) {
  TempDir dir;
  const auto grid = small_grid();
  FakeRunner runner;
  runner.fail_cells = {2, 7};
  SweepRunOptions options;
  options.out_dir = dir.path;
  const std::atomic<bool> no_stop{false};
  const SweepRunSummary first = run_sweep(grid, options, runner, {}, no_stop);
  EXPECT_EQ(first.counts.failed, 2u);
  EXPECT_EQ(first.counts.ran, grid.size() - 2);
  const auto rows = read_results_csv(dir.path / "results.csv");
  EXPECT_FALSE(rows[2].has_episode);
  EXPECT_EQ(rows[2].status, "failed: a3rig run exited with status 2; no episode.json");
  EXPECT_TRUE(rows[3].has_episode);
  EXPECT_EQ(rows[3].status, "completed");
  const auto groups = aggregate(rows);
  int missing = 0;
  for (const auto& g : groups) missing += g.n_missing;
  EXPECT_EQ(missing, 2);

  runner.fail_cells.clear();
  runner.ran();
  const SweepRunSummary second = run_sweep(grid, options, runner, {}, no_stop);
  EXPECT_EQ(runner.ran(), (std::vector<std::size_t>{2, 7}));
  EXPECT_EQ(second.counts.failed, 0u);
}

TEST(SweepResume, AStoppedSweepLeavesTheRestNotRun) {
  TempDir dir;
  const auto grid = small_grid();
  FakeRunner runner;
  SweepRunOptions options;
  options.out_dir = dir.path;
  const std::atomic<bool> stopped{true};
  const std::atomic<bool> no_stop{false};
  options.shard = parse_shard("0/2");
  run_sweep(grid, options, runner, {}, no_stop);  // half the cells complete
  runner.ran();
  options.shard = Shard{};
  const SweepRunSummary summary = run_sweep(grid, options, runner, {}, stopped);
  EXPECT_TRUE(summary.stopped);
  EXPECT_TRUE(runner.ran().empty());
  EXPECT_EQ(summary.counts.skipped, grid.size() / 2);  // complete cells keep their rows
  const auto rows = read_results_csv(dir.path / "results.csv");
  ASSERT_EQ(rows.size(), grid.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i % 2 == 0) {
      EXPECT_EQ(rows[i].status, "completed");
    } else {
      EXPECT_EQ(rows[i].status, "not_run: the sweep was stopped");
    }
  }
}

TEST(SweepResume, ShardsWriteTheirOwnFilesAndMergeIntoTheWholeGrid) {
  TempDir dir;
  const auto grid = small_grid();
  FakeRunner runner;
  const std::atomic<bool> no_stop{false};
  std::set<std::size_t> ran;
  for (int i = 0; i < 3; ++i) {
    SweepRunOptions options;
    options.out_dir = dir.path;
    options.shard = parse_shard(std::to_string(i) + "/3");
    const SweepRunSummary s = run_sweep(grid, options, runner, {}, no_stop);
    EXPECT_EQ(s.results_path.filename(), "results.shard-" + std::to_string(i) + "-of-3.csv");
    for (const std::size_t k : runner.ran()) {
      EXPECT_EQ(k % 3, static_cast<std::size_t>(i));
      EXPECT_TRUE(ran.insert(k).second) << "cell " << k << " ran twice";
    }
  }
  EXPECT_EQ(ran.size(), grid.size());
  EXPECT_FALSE(fs::exists(dir.path / "results.csv"));
  const MergedReport merged = reaggregate(dir.path);
  EXPECT_EQ(merged.rows, grid.size());
  EXPECT_EQ(merged.report.aggregates.size(), grid.size() / 2);  // two seeds per group
  for (const auto& g : merged.report.aggregates) EXPECT_EQ(g.n, 2);
}

TEST(SweepResume, NoMoreThanJobsCellsRunAtOnce) {
  TempDir dir;
  const auto grid = small_grid();
  FakeRunner runner;
  runner.run_time = std::chrono::milliseconds(30);
  SweepRunOptions options;
  options.out_dir = dir.path;
  options.jobs = 3;
  std::size_t updates = 0;
  const std::atomic<bool> no_stop{false};
  run_sweep(grid, options, runner, [&](const ProgressCounts&) { ++updates; }, no_stop);
  EXPECT_EQ(runner.max_running(), 3);
  EXPECT_EQ(updates, grid.size());
}

TEST(SweepProgress, TheLineShowsCountsRateAndEta) {
  ProgressCounts c;
  c.total = 100;
  c.ran = 20;
  c.skipped = 5;
  c.to_run = 95;
  c.elapsed_s = 10.0;  // 2 episodes/s; 75 to go
  const std::string line = progress_line(c, 20);
  EXPECT_EQ(line, "[#####---------------] 25/100  25%  ran 20  skipped 5  failed 0  2.00 episodes/s  ETA 38s");
  c.ran = 95;
  c.elapsed_s = 4000.0;
  EXPECT_NE(progress_line(c, 20).find("done in 1h06m"), std::string::npos) << progress_line(c, 20);
  EXPECT_EQ(format_duration(187.0), "3m07s");
  c.ran = 0;
  c.skipped = 10;
  c.to_run = 90;
  EXPECT_NE(progress_line(c, 20).find("ETA ?"), std::string::npos);
  // Resumed: 90 of 100 complete at the start; 5 of the other 10 run in 10 s.
  c.skipped = 80;
  c.ran = 5;
  c.to_run = 10;
  c.elapsed_s = 10.0;
  EXPECT_NE(progress_line(c, 20).find("0.50 episodes/s  ETA 10s"), std::string::npos) << progress_line(c, 20);
}

TEST(SweepResume, ACellThatBrokeTheRealTimeContractIsRunAgainABoundedNumberOfTimes) {
  TempDir dir;
  const auto grid = small_grid();
  FakeRunner runner;
  runner.violate_times[3] = 1;   // fine on the second run
  runner.violate_times[5] = 10;  // never fine
  SweepRunOptions options;
  options.out_dir = dir.path;
  options.realtime_retries = 2;
  std::atomic<bool> stop{false};
  const SweepRunSummary s = run_sweep(grid, options, runner, {}, stop);
  EXPECT_EQ(s.realtime_reruns, 1u + 2u);
  EXPECT_TRUE(s.rows[3].has_episode);
  EXPECT_EQ(s.rows[3].status, "completed");
  EXPECT_FALSE(s.rows[5].has_episode);
  EXPECT_EQ(s.rows[5].status.rfind("failed: the run ended realtime_violated", 0), 0u) << s.rows[5].status;
  EXPECT_NE(s.rows[5].status.find("after 2 reruns"), std::string::npos) << s.rows[5].status;
  EXPECT_EQ(s.counts.failed, 1u);
  // A resumed sweep tries the violated cell again; the others are complete.
  runner.ran();
  runner.violate_times[5] = 0;
  const SweepRunSummary again = run_sweep(grid, options, runner, {}, stop);
  EXPECT_EQ(runner.ran(), std::vector<std::size_t>{5});
  EXPECT_EQ(again.counts.failed, 0u);
}

}  // namespace
}  // namespace a3::rigs::sweep
