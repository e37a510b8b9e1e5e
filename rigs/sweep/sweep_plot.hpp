// The sweep's plots (gnuplot, PNG): for each scenario × agent, α³, SP and success rate against
// the mean think time per agent turn, one line per slice, with the 95 % confidence band of each
// (filledcurves). Where an interval is undefined (one episode) the band collapses on the mean.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rigs/sweep/aggregate.hpp"

namespace a3::rigs::sweep {

struct PlotOutcome {
  std::vector<std::filesystem::path> pngs;  // plots_dir/sweep_<scenario>_<agent>.png
  std::string problem;                      // "" when every plot was drawn
};

// Writes the data (.dat), the gnuplot scripts (.gp) and runs gnuplot in plots_dir.
PlotOutcome write_sweep_plots(const std::filesystem::path& plots_dir, const std::vector<AggregateRow>& rows);

}  // namespace a3::rigs::sweep
