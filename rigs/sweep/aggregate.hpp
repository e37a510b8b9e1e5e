// Aggregates of a sweep (aggregate.csv): per scenario × agent × think time × slice, the number
// of episodes, mean α³ and SP with Student's t 95 % intervals (clamped to [0, 1], where the
// scores live), the success rate with its Wilson 95 % interval, and how many of the failures were
// the agent's own (a fault inside the agent, rigs/outputs/agent_faults.hpp). Cells without a complete
// episode are counted apart (n_missing) and enter no statistic.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rigs/sweep/confidence.hpp"
#include "rigs/sweep/results_table.hpp"

namespace a3::rigs::sweep {

struct AggregateRow {
  std::string scenario;
  std::string agent;
  std::string think_time;
  double think_time_mean_s = 0.0;
  std::string slice;
  int n = 0;          // episodes
  int n_missing = 0;  // cells without a complete episode
  double alpha3_mean = 0.0;
  std::optional<Interval> alpha3_ci;  // none for n < 2
  double sp_mean = 0.0;
  std::optional<Interval> sp_ci;
  int successes = 0;
  double success_rate = 0.0;
  std::optional<Interval> success_ci;  // none for n = 0
  double mission_time_mean_s = 0.0;
  int agent_failures = 0;  // failed episodes with a fault inside the agent (ResultRow::agent_failure)
};

// Groups in the order the rows first name them.
std::vector<AggregateRow> aggregate(const std::vector<ResultRow>& rows);

// Writes the table whole or not at all (common/atomic_file.hpp); throws common::OutputError.
void write_aggregate_csv(const std::filesystem::path& path, const std::vector<AggregateRow>& rows);

}  // namespace a3::rigs::sweep
