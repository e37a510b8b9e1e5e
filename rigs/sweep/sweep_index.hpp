// index.html of a sweep folder: the aggregate plots, the aggregate table (mean α³, SP and
// success with their 95 % intervals per point) and a table of every cell with its status and
// scores, each linking to the cell's episode report (report.html beside its episode.json, or
// the episode itself when the cell has no report). Plain HTML with relative links: it opens
// from the sweep's folder, offline.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rigs/sweep/aggregate.hpp"
#include "rigs/sweep/results_table.hpp"

namespace a3::rigs::sweep {

std::string sweep_index_html(const std::filesystem::path& out_dir, const std::vector<ResultRow>& rows,
                             const std::vector<AggregateRow>& aggregates,
                             const std::vector<std::filesystem::path>& pngs);

// Writes out_dir/index.html atomically; throws common::OutputError naming the file.
std::filesystem::path write_sweep_index(const std::filesystem::path& out_dir, const std::vector<ResultRow>& rows,
                                        const std::vector<AggregateRow>& aggregates,
                                        const std::vector<std::filesystem::path>& pngs);

}  // namespace a3::rigs::sweep
