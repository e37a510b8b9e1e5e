// results.csv written and read back (quoting, errors with file, line and column), results files
// of shards merged, and the aggregate's means, rates and 95 % intervals on a hand-made set.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "common/csv_text.hpp"
#include "rigs/sweep/aggregate.hpp"
#include "rigs/sweep/results_table.hpp"
#include "rigs/sweep/sweep_report.hpp"
#include "tests/test_support.hpp"

namespace a3::rigs::sweep {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("a3-sweep-results-" + std::to_string(::getpid()) + "-" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

ResultRow episode_row(const std::string& think, const std::string& slice, uint64_t seed, double alpha3, double sp,
                      bool success) {
  ResultRow r;
  r.scenario = "survey-field";
  r.agent = "scripted";
  r.think_time = think;
  r.think_time_mean_s = think == "uniform:1,4" ? 2.5 : 0.0;
  r.slice = slice;
  r.seed = seed;
  r.status = "completed";
  r.has_episode = true;
  r.valid = true;
  r.success = success;
  r.alpha3 = alpha3;
  r.to = 0.9;
  r.sp = sp;
  r.tc = 0.8;
  r.iq = 0.7;
  r.nr = 0.6;
  r.cc = 0.5;
  r.mission_time_s = 100.0 + static_cast<double>(seed);
  r.wall_time_s = 1.5;
  r.episode = "cells/x/seed-" + std::to_string(seed) + "/episode.json";
  return r;
}

ResultRow missing_row(const std::string& think, const std::string& slice, uint64_t seed) {
  ResultRow r = episode_row(think, slice, seed, 0, 0, false);
  r.has_episode = false;
  r.status = "failed: a3rig run exited with status 2, see \"run.log\"";
  r.mission_time_s = r.wall_time_s = std::nan("");
  r.episode.clear();
  return r;
}

std::vector<ResultRow> hand_made_set() {
  return {episode_row("0", "eMBB", 1, 0.6, 1.0, true), episode_row("0", "eMBB", 2, 0.7, 1.0, true),
          episode_row("0", "eMBB", 3, 0.8, 0.5, false), episode_row("uniform:1,4", "URLLC", 1, 0.3, 1.0, false),
          missing_row("uniform:1,4", "URLLC", 2)};
}

// aggregate.csv as column name → field, one map per line.
std::vector<std::map<std::string, std::string>> read_table(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const auto header = common::csv_fields(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const auto fields = common::csv_fields(line);
    EXPECT_EQ(fields.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

TEST(ResultsTable, RowsSurviveTheRoundTripIncludingQuotedFields) {
  TempDir dir;
  const auto rows = hand_made_set();
  write_results_csv(dir.path / "results.csv", rows);
  const auto back = read_results_csv(dir.path / "results.csv");
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_EQ(back[3].think_time, "uniform:1,4");
  EXPECT_DOUBLE_EQ(back[3].think_time_mean_s, 2.5);
  EXPECT_DOUBLE_EQ(back[2].alpha3, 0.8);
  EXPECT_DOUBLE_EQ(back[2].sp, 0.5);
  EXPECT_FALSE(back[2].success);
  EXPECT_TRUE(back[1].success);
  EXPECT_DOUBLE_EQ(back[1].mission_time_s, 102.0);
  EXPECT_FALSE(back[4].has_episode);
  EXPECT_EQ(back[4].status, rows[4].status);
  EXPECT_TRUE(std::isnan(back[4].mission_time_s));
}

TEST(ResultsTable, MalformedFilesAreNamedWithLineAndColumn) {
  TempDir dir;
  std::ofstream(dir.path / "bad-header.csv") << "scenario,agent\n";
  try {
    read_results_csv(dir.path / "bad-header.csv");
    FAIL() << "a wrong header was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad-header.csv:1:"), std::string::npos) << e.what();
  }
  write_results_csv(dir.path / "results.csv", {episode_row("0", "eMBB", 1, 0.6, 1.0, true)});
  std::string text;
  {
    std::ifstream in(dir.path / "results.csv");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto at = text.find(",0.6,");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 5, ",zero,");
  std::ofstream(dir.path / "bad-value.csv") << text;
  try {
    read_results_csv(dir.path / "bad-value.csv");
    FAIL() << "a non-number α³ was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad-value.csv:2: column alpha3: 'zero'"), std::string::npos) << e.what();
  }
}

TEST(ResultsTable, AgentFaultsFlagTheAgentsOwnFailures) {
  TempDir dir;
  std::vector<ResultRow> rows = hand_made_set();
  rows[2].agent_faults = "refused_repeated;timeout_not_retried";  // failed, with faults: the agent's failure
  rows[1].agent_faults = "timeout_not_retried";                   // succeeded anyway: not a failure
  EXPECT_TRUE(rows[2].agent_failure());
  EXPECT_FALSE(rows[1].agent_failure());
  EXPECT_FALSE(rows[3].agent_failure());  // failed without a fault: the link's or the world's
  write_results_csv(dir.path / "results.csv", rows);
  const auto table = read_table(dir.path / "results.csv");
  EXPECT_EQ(table[2].at("agent_failure"), "1");
  EXPECT_EQ(table[1].at("agent_failure"), "0");
  EXPECT_EQ(table[4].at("agent_failure"), "");  // no episode
  const auto back = read_results_csv(dir.path / "results.csv");
  EXPECT_EQ(back[2].agent_faults, rows[2].agent_faults);
  EXPECT_TRUE(back[2].agent_failure());

  const auto aggregates = aggregate(rows);
  ASSERT_FALSE(aggregates.empty());
  EXPECT_EQ(aggregates[0].agent_failures, 1);
  write_aggregate_csv(dir.path / "aggregate.csv", aggregates);
  EXPECT_EQ(read_table(dir.path / "aggregate.csv")[0].at("agent_failures"), "1");

  // A flag that disagrees with the faults and the success is named.
  std::string text;
  {
    std::ifstream in(dir.path / "results.csv");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto at = text.find(",timeout_not_retried,0\n");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string(",timeout_not_retried,0").size(), ",timeout_not_retried,1");
  std::ofstream(dir.path / "bad-flag.csv") << text;
  try {
    read_results_csv(dir.path / "bad-flag.csv");
    FAIL() << "an agent_failure flag that disagrees was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad-flag.csv:3: column agent_failure"), std::string::npos) << e.what();
  }
}

TEST(ResultsTable, ATableFromBeforeTheAgentFaultColumnsStillReads) {
  TempDir dir;
  write_results_csv(dir.path / "results.csv", hand_made_set());
  std::ifstream in(dir.path / "results.csv");
  std::ostringstream older;
  for (std::string line; std::getline(in, line);) {
    auto fields = common::csv_fields(line);
    fields.resize(fields.size() - 2);
    for (std::size_t i = 0; i < fields.size(); ++i) older << (i ? "," : "") << common::csv_cell(fields[i]);
    older << "\n";
  }
  std::ofstream(dir.path / "older.csv") << older.str();
  const auto back = read_results_csv(dir.path / "older.csv");
  ASSERT_EQ(back.size(), 5u);
  EXPECT_DOUBLE_EQ(back[2].alpha3, 0.8);
  EXPECT_TRUE(back[2].agent_faults.empty());
}

TEST(ResultsTable, ShardFilesMergeIntoOneRowPerCell) {
  TempDir dir;
  const auto rows = hand_made_set();
  write_results_csv(dir.path / "results.shard-0-of-2.csv", {rows[0], rows[4], rows[2]});
  const ResultRow rerun = episode_row("uniform:1,4", "URLLC", 2, 0.2, 0.5, false);
  write_results_csv(dir.path / "results.shard-1-of-2.csv", {rows[1], rows[3], rerun, rows[0]});
  std::ofstream(dir.path / "results-notes.csv") << "not a results file\n";
  const auto files = result_files(dir.path);
  ASSERT_EQ(files.size(), 2u);
  const auto merged = merge_result_files(files);
  ASSERT_EQ(merged.size(), 5u);  // rows[0] twice, identical: once
  int with_episode = 0;
  for (const auto& r : merged) with_episode += r.has_episode;
  EXPECT_EQ(with_episode, 5);  // the re-run cell's episode wins over its failure
  // Sorted by scenario, agent, think time (mean), slice, seed.
  EXPECT_EQ(merged[0].seed, 1u);
  EXPECT_EQ(merged[2].seed, 3u);
  EXPECT_EQ(merged[4].think_time, "uniform:1,4");
  EXPECT_EQ(merged[4].seed, 2u);

  ResultRow changed = rows[1];
  changed.alpha3 = 0.1;
  write_results_csv(dir.path / "results.csv", {changed});
  try {
    merge_result_files(result_files(dir.path));
    FAIL() << "two different episodes of one cell were merged";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("results.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("results.shard-1-of-2.csv"), std::string::npos) << e.what();
  }
}

TEST(Aggregate, MeansRatesAndIntervalsOfAHandMadeSet) {
  const auto groups = aggregate(hand_made_set());
  ASSERT_EQ(groups.size(), 2u);
  const AggregateRow& a = groups[0];
  EXPECT_EQ(a.think_time, "0");
  EXPECT_EQ(a.n, 3);
  EXPECT_EQ(a.n_missing, 0);
  EXPECT_NEAR(a.alpha3_mean, 0.7, 1e-12);
  ASSERT_TRUE(a.alpha3_ci.has_value());
  EXPECT_NEAR(a.alpha3_ci->lo, 0.7 - 4.30265 * 0.1 / std::sqrt(3.0), 1e-4);  // 0.4516
  EXPECT_NEAR(a.alpha3_ci->hi, 0.7 + 4.30265 * 0.1 / std::sqrt(3.0), 1e-4);  // 0.9484
  EXPECT_NEAR(a.sp_mean, 2.5 / 3.0, 1e-12);
  ASSERT_TRUE(a.sp_ci.has_value());
  EXPECT_NEAR(a.sp_ci->lo, 2.5 / 3.0 - 4.30265 * std::sqrt(1.0 / 12.0) / std::sqrt(3.0), 1e-4);
  EXPECT_DOUBLE_EQ(a.sp_ci->hi, 1.0);  // clamped: SP lives in [0, 1]
  EXPECT_EQ(a.successes, 2);
  EXPECT_NEAR(a.success_rate, 2.0 / 3.0, 1e-12);
  ASSERT_TRUE(a.success_ci.has_value());
  EXPECT_NEAR(a.success_ci->lo, 0.2077, 1e-4);  // Wilson 95 % of 2/3
  EXPECT_NEAR(a.success_ci->hi, 0.9385, 1e-4);
  EXPECT_NEAR(a.mission_time_mean_s, 102.0, 1e-12);

  const AggregateRow& b = groups[1];
  EXPECT_EQ(b.think_time, "uniform:1,4");
  EXPECT_EQ(b.n, 1);
  EXPECT_EQ(b.n_missing, 1);
  EXPECT_NEAR(b.alpha3_mean, 0.3, 1e-12);
  EXPECT_FALSE(b.alpha3_ci.has_value());  // one episode: no t-interval
  ASSERT_TRUE(b.success_ci.has_value());
  EXPECT_DOUBLE_EQ(b.success_ci->lo, 0.0);
  EXPECT_NEAR(b.success_ci->hi, 0.7935, 1e-4);  // Wilson 95 % of 0/1
}

TEST(Aggregate, TheCsvHoldsTheNumbersAndEmptyFieldsForUndefinedIntervals) {
  TempDir dir;
  write_aggregate_csv(dir.path / "aggregate.csv", aggregate(hand_made_set()));
  const auto table = read_table(dir.path / "aggregate.csv");
  ASSERT_EQ(table.size(), 2u);
  EXPECT_EQ(table[0].at("n"), "3");
  EXPECT_EQ(table[0].at("alpha3_mean"), "0.700000");
  EXPECT_EQ(table[0].at("alpha3_ci95_lo"), "0.451586");
  EXPECT_EQ(table[0].at("alpha3_ci95_hi"), "0.948414");
  EXPECT_EQ(table[0].at("SP_ci95_hi"), "1.000000");
  EXPECT_EQ(table[0].at("success_rate"), "0.666667");
  EXPECT_EQ(table[1].at("think_time"), "uniform:1,4");
  EXPECT_EQ(table[1].at("n_missing"), "1");
  EXPECT_EQ(table[1].at("alpha3_ci95_lo"), "");
  EXPECT_EQ(table[1].at("SP_ci95_hi"), "");
}

TEST(SweepReport, PlotOnlyMergesShardsAndDrawsTheFigure) {
  TempDir dir;
  const auto rows = hand_made_set();
  write_results_csv(dir.path / "results.shard-0-of-2.csv", {rows[0], rows[2], rows[4]});
  write_results_csv(dir.path / "results.shard-1-of-2.csv", {rows[1], rows[3]});
  const MergedReport merged = reaggregate(dir.path);
  EXPECT_EQ(merged.merged_files.size(), 2u);
  EXPECT_EQ(merged.rows, 5u);
  EXPECT_EQ(read_results_csv(dir.path / "results.csv").size(), 5u);
  EXPECT_EQ(read_table(dir.path / "aggregate.csv").size(), 2u);
  ASSERT_TRUE(merged.report.plots.problem.empty()) << merged.report.plots.problem;
  ASSERT_EQ(merged.report.plots.pngs.size(), 1u);
  EXPECT_EQ(merged.report.plots.pngs[0].filename(), "sweep_survey-field_scripted.png");
  std::ifstream png(merged.report.plots.pngs[0], std::ios::binary);
  char signature[8] = {};
  png.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  EXPECT_THROW(reaggregate(dir.path / "nowhere"), std::runtime_error);
}

}  // namespace
}  // namespace a3::rigs::sweep
