// Writing the leaderboard in the public release's columns: an aligned text table, CSV, JSON or
// Markdown. CSV and JSON carry full precision (shortest round-trip); the table and Markdown
// round to 5 decimals as the paper's tables do.
#pragma once

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "eval/model_summary.hpp"

namespace a3::eval {

enum class LeaderboardFormat { kTable, kCsv, kJson, kMarkdown };

// "table" | "csv" | "json" | "markdown"; throws std::invalid_argument otherwise.
LeaderboardFormat parse_leaderboard_format(std::string_view name);

// The release's column names, in order.
const std::vector<std::string>& leaderboard_columns();

void write_leaderboard(std::ostream& out, const std::vector<ModelSummary>& rows,
                       LeaderboardFormat format);

// Shortest decimal text that reads back as the same double ("0.97644676488595226").
std::string format_double(double x);

}  // namespace a3::eval
