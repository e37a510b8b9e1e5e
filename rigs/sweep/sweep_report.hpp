// The aggregate and the plots of a sweep folder, from its results rows — right after a sweep,
// or later from the results files alone (`a3rig sweep --plot-only DIR`), which is also how the
// shards of a cluster run are merged: their results.shard-I-of-N.csv files, gathered in one
// folder, become one results.csv.
#pragma once

#include <filesystem>
#include <vector>

#include "rigs/sweep/aggregate.hpp"
#include "rigs/sweep/results_table.hpp"
#include "rigs/sweep/sweep_plot.hpp"

namespace a3::rigs::sweep {

struct SweepReport {
  std::filesystem::path aggregate_path;  // out_dir/aggregate.csv
  std::vector<AggregateRow> aggregates;
  PlotOutcome plots;  // in out_dir/plots/
  std::filesystem::path index_path;  // out_dir/index.html (sweep_index.hpp)
};

SweepReport write_report(const std::filesystem::path& out_dir, const std::vector<ResultRow>& rows);

struct MergedReport {
  std::vector<std::filesystem::path> merged_files;
  std::size_t rows = 0;
  SweepReport report;
};

// Merges every results file of out_dir into out_dir/results.csv and writes the report. Throws
// std::runtime_error when the folder holds no results file.
MergedReport reaggregate(const std::filesystem::path& out_dir);

}  // namespace a3::rigs::sweep
