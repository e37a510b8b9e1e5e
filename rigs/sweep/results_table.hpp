// The sweep's results table (results.csv): one row per cell with its keys, how the episode
// ended and its α³-Bench scores. Written by a sweep, read back by `a3rig sweep --plot-only` to
// re-aggregate, and merged across shards (results.csv and results.shard-I-of-N.csv).
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace a3::rigs::sweep {

struct ResultRow {
  std::string scenario;
  std::string agent;
  std::string think_time;
  double think_time_mean_s = 0.0;
  std::string slice;
  uint64_t seed = 0;
  // The episode's _rig.status (completed, time_limit, crashed), or why the cell has no
  // complete episode ("failed: ..."); only rows with has_episode enter the aggregates.
  std::string status;
  bool has_episode = false;
  bool success = false;
  bool valid = false;  // a valid α³-Bench episode; an invalid one scores 0 on every pillar
  double alpha3 = 0.0, to = 0.0, sp = 0.0, tc = 0.0, iq = 0.0, nr = 0.0, cc = 0.0;
  double mission_time_s = std::numeric_limits<double>::quiet_NaN();
  double wall_time_s = std::numeric_limits<double>::quiet_NaN();
  std::string episode;  // episode.json relative to the sweep's folder
  // The kinds of _rig.agent_faults (rigs/outputs/agent_faults.hpp), sorted, ";"-joined; empty: none.
  std::string agent_faults;
  // A failed episode with a fault inside the agent: the agent's failure, not the link's.
  bool agent_failure() const { return has_episode && !success && !agent_faults.empty(); }
};

// The header line's column names, in order.
const std::vector<std::string>& results_columns();

// Writes the table whole or not at all (common/atomic_file.hpp), creating missing folders;
// throws common::OutputError ("<file>: <reason>").
void write_results_csv(const std::filesystem::path& path, const std::vector<ResultRow>& rows);
// Throws std::runtime_error naming the file, line and column of anything malformed.
std::vector<ResultRow> read_results_csv(const std::filesystem::path& path);

// The result files of a sweep folder: results.csv and results.shard-*-of-*.csv, sorted.
std::vector<std::filesystem::path> result_files(const std::filesystem::path& out_dir);
// Rows of several files, one per cell (scenario, agent, think time, slice, seed): a cell met
// twice with the same values is kept once; with different values, the row with an episode
// wins over one without, and two different episodes are an error naming both files.
std::vector<ResultRow> merge_result_files(const std::vector<std::filesystem::path>& files);

}  // namespace a3::rigs::sweep
