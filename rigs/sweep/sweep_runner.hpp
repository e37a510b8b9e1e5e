// Runs the cells of a sweep (or of one shard) up to `jobs` at a time, skipping complete cells
// (resume), and writes the results table: results.csv, or results.shard-I-of-N.csv for a shard
// so that shards sharing a folder never overwrite each other.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

#include "rigs/sweep/cell_runner.hpp"
#include "rigs/sweep/progress.hpp"
#include "rigs/sweep/results_table.hpp"
#include "rigs/sweep/sweep_grid.hpp"

namespace a3::rigs::sweep {

struct SweepRunOptions {
  std::filesystem::path out_dir = "out/sweep";
  Shard shard;
  int jobs = 1;
  bool rerun_complete = false;  // run every cell again, complete or not
  int realtime_retries = 2;     // reruns of a cell whose run broke the real-time contract
};

struct SweepRunSummary {
  ProgressCounts counts;
  bool stopped = false;  // asked to stop: the cells not started have rows "not_run: ..."
  std::vector<ResultRow> rows;  // one per cell of the shard, in grid order
  std::size_t realtime_reruns = 0;  // runs repeated because the real-time contract broke
  std::filesystem::path results_path;
};

using ProgressCallback = std::function<void(const ProgressCounts& counts)>;

// The results file of a shard: results.csv for 0/1, else results.shard-I-of-N.csv.
std::filesystem::path results_path(const std::filesystem::path& out_dir, const Shard& shard);
// The shards I of I/count whose results file is not in out_dir (a task that never ran or was killed).
std::vector<int> missing_shards(const std::filesystem::path& out_dir, int count);

SweepRunSummary run_sweep(const std::vector<SweepCell>& grid, const SweepRunOptions& options, CellRunner& runner,
                          const ProgressCallback& progress, const std::atomic<bool>& stop);

}  // namespace a3::rigs::sweep
