// `--plots DIR`: the paper's leaderboard figures as PNG, drawn by gnuplot (Debian's
// gnuplot-nox): mean α³ per model with its 95 % interval, α³_rel per model, α³ per 1k tokens and
// per second against the mean score, and mean generation time and tokens per model. The data
// (leaderboard.tsv) and the gnuplot script (plots.gp) are written beside the figures so a figure
// can be redrawn or restyled by hand.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "eval/model_summary.hpp"

namespace a3::eval {

// The PNG files written, in DIR.
const std::vector<std::string>& leaderboard_plot_files();

// Writes the data, the script and the PNGs into dir (created if needed), each whole or not at
// all (a PNG is renamed into place only when gnuplot succeeded and it is complete). Throws
// std::runtime_error when gnuplot is missing or fails (its message included), and
// common::OutputError ("<file>: <reason>") when a file cannot be written (a full disk).
void write_leaderboard_plots(const std::filesystem::path& dir,
                             const std::vector<ModelSummary>& rows);

}  // namespace a3::eval
