// A small real sweep: the traffic-conflict scenario with think times 0 and 60 s on one slice and
// one seed, each cell a child `a3rig run` in virtual time. The slow agent misses the conflict
// (a separation breach: SP 0.5) and the fast one does not; results.csv, aggregate.csv and the
// PNG are written, and a resumed sweep runs nothing. A run that fails or hangs is recorded.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "rigs/sweep/sweep_report.hpp"
#include "rigs/sweep/sweep_runner.hpp"
#include "tests/integration/run_command.hpp"
#include "tests/test_support.hpp"

namespace a3::rigs::sweep {
namespace {

namespace fs = std::filesystem;

TEST(SweepEndToEnd, ASlowAgentBreachesSeparationAndTheFigureIsDrawn) {
  const fs::path out = fs::temp_directory_path() / ("a3-sweep-e2e-" + std::to_string(::getpid()));
  fs::remove_all(out);
  ::setenv("A3_SHARED_DIR", a3::test::shared_dir().c_str(), 0);
  const auto grid = expand_grid(make_axes("traffic-conflict", "scripted", "0,90", "URLLC", "1"));
  ASSERT_EQ(grid.size(), 2u);
  ChildProcessOptions child;
  child.a3rig_exe = A3RIG_EXE;
  child.cell_timeout_s = 120.0;
  ChildProcessCellRunner runner(child);
  SweepRunOptions options;
  options.out_dir = out;
  options.jobs = 2;
  const std::atomic<bool> no_stop{false};
  // `--dry-run` says what is left and how long it will take (issue 34), before and after.
  const std::string dry_run = std::string(A3RIG_EXE) + " sweep --dry-run --scenarios traffic-conflict --agents scripted " +
                              "--think-times 0,90 --slices URLLC --seeds 1 --jobs 1 --out " + a3::test::quote(out.string());
  auto dry = a3::test::run_command(dry_run, true);
  EXPECT_EQ(dry.exit_status, 0) << dry.output;
  EXPECT_NE(dry.output.find("2 cells to run (0 already complete): about 2 s (virtual time"), std::string::npos)
      << dry.output;

  const SweepRunSummary summary = run_sweep(grid, options, runner, {}, no_stop);
  ASSERT_EQ(summary.counts.ran, 2u) << summary.rows[0].status << "\n" << summary.rows[1].status;
  const auto rows = read_results_csv(out / "results.csv");
  ASSERT_EQ(rows.size(), 2u);
  const ResultRow& fast = rows[0];
  const ResultRow& slow = rows[1];
  EXPECT_EQ(fast.think_time, "0");
  EXPECT_EQ(slow.think_time, "90");
  EXPECT_DOUBLE_EQ(slow.think_time_mean_s, 90.0);
  ASSERT_TRUE(fast.valid && slow.valid);
  EXPECT_DOUBLE_EQ(fast.sp, 1.0);
  EXPECT_DOUBLE_EQ(slow.sp, 0.5);
  EXPECT_GT(fast.alpha3, slow.alpha3);
  EXPECT_GT(fast.mission_time_s, 0.0);
  EXPECT_TRUE(fs::exists(out / fast.episode));
  std::ifstream slow_episode(out / slow.episode);
  EXPECT_TRUE(nlohmann::json::parse(slow_episode)["final_state"]["safety_flags"]["separation_breach"].get<bool>());
  EXPECT_TRUE(fs::exists(fs::path(out / slow.episode).parent_path() / "run.log"));

  const SweepReport report = write_report(out, summary.rows);
  ASSERT_EQ(report.aggregates.size(), 2u);
  EXPECT_DOUBLE_EQ(report.aggregates[1].sp_mean, 0.5);
  ASSERT_TRUE(report.plots.problem.empty()) << report.plots.problem;
  ASSERT_EQ(report.plots.pngs.size(), 1u);
  EXPECT_GT(fs::file_size(report.plots.pngs[0]), 10000u);

  dry = a3::test::run_command(dry_run, true);
  EXPECT_NE(dry.output.find("0 cells to run (2 already complete): nothing to run"), std::string::npos) << dry.output;

  const SweepRunSummary again = run_sweep(grid, options, runner, {}, no_stop);
  EXPECT_EQ(again.counts.skipped, 2u);
  EXPECT_EQ(again.counts.ran, 0u);
  fs::remove_all(out);
}

TEST(SweepEndToEnd, ARunThatFailsOrHangsIsRecordedWithItsLog) {
  const fs::path out = fs::temp_directory_path() / ("a3-sweep-e2e-fail-" + std::to_string(::getpid()));
  fs::remove_all(out);
  // A scenario file that does not exist: `a3rig run` exits 2 (bad input) without an episode.
  const auto grid = expand_grid(make_axes(out.string() + "/missing-scenario.json", "scripted", "0", "URLLC", "1"));
  ChildProcessOptions child;
  child.a3rig_exe = A3RIG_EXE;
  ChildProcessCellRunner runner(child);
  SweepRunOptions options;
  options.out_dir = out;
  const std::atomic<bool> no_stop{false};
  const SweepRunSummary failed = run_sweep(grid, options, runner, {}, no_stop);
  EXPECT_EQ(failed.counts.failed, 1u);
  ASSERT_EQ(failed.rows.size(), 1u);
  EXPECT_FALSE(failed.rows[0].has_episode);
  EXPECT_NE(failed.rows[0].status.find("exited with status 2"), std::string::npos) << failed.rows[0].status;
  std::ifstream log(cell_dir(out, grid[0]) / "run.log");
  const std::string log_text((std::istreambuf_iterator<char>(log)), {});
  EXPECT_NE(log_text.find("missing-scenario.json"), std::string::npos) << log_text;

  // A run that outlasts its wall-clock limit is ended and recorded as timed out.
  const auto slow = expand_grid(make_axes("traffic-conflict", "scripted", "60", "URLLC", "1"));
  child.cell_timeout_s = 0.3;
  ChildProcessCellRunner impatient(child);
  options.rerun_complete = true;
  const SweepRunSummary timed_out = run_sweep(slow, options, impatient, {}, no_stop);
  ASSERT_EQ(timed_out.rows.size(), 1u);
  EXPECT_NE(timed_out.rows[0].status.find("timed out after 0.3 s"), std::string::npos) << timed_out.rows[0].status;
  fs::remove_all(out);
}

}  // namespace
}  // namespace a3::rigs::sweep
