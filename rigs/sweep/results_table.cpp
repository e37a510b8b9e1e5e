// Writing, reading and merging results.csv.
#include "rigs/sweep/results_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "common/atomic_file.hpp"
#include "common/csv_text.hpp"

namespace a3::rigs::sweep {
namespace {

std::string number(double x) {
  if (!std::isfinite(x)) return "";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.10g", x);
  return buffer;
}

std::string row_line(const ResultRow& r) {
  const bool e = r.has_episode;
  const std::vector<std::string> fields = {
      r.scenario, r.agent, r.think_time, number(r.think_time_mean_s), r.slice, std::to_string(r.seed), r.status,
      e ? (r.success ? "1" : "0") : "", e ? (r.valid ? "1" : "0") : "", e ? number(r.alpha3) : "",
      e ? number(r.to) : "", e ? number(r.sp) : "", e ? number(r.tc) : "", e ? number(r.iq) : "",
      e ? number(r.nr) : "", e ? number(r.cc) : "", number(r.mission_time_s), number(r.wall_time_s), r.episode,
      r.agent_faults, e ? (r.agent_failure() ? "1" : "0") : ""};
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + common::csv_cell(fields[i]);
  return line;
}

struct FieldReader {
  const std::filesystem::path& path;
  int line_number;
  const std::vector<std::string>& fields;

  std::string where(std::size_t column) const {
    return path.string() + ":" + std::to_string(line_number) + ": column " + results_columns()[column];
  }
  const std::string& text(std::size_t column) const { return fields[column]; }
  double real(std::size_t column, bool allow_empty) const {
    const std::string& f = fields[column];
    if (f.empty()) {
      if (allow_empty) return std::nan("");
      throw std::runtime_error(where(column) + ": empty (expected a number)");
    }
    try {
      std::size_t used = 0;
      const double x = std::stod(f, &used);
      if (used == f.size() && std::isfinite(x)) return x;
    } catch (const std::exception&) {
    }
    throw std::runtime_error(where(column) + ": '" + f + "' is not a number");
  }
  bool flag(std::size_t column) const {
    if (fields[column] == "1") return true;
    if (fields[column] == "0") return false;
    throw std::runtime_error(where(column) + ": '" + fields[column] + "' is not 0 or 1");
  }
  uint64_t seed(std::size_t column) const {
    const std::string& f = fields[column];
    if (f.empty() || !std::all_of(f.begin(), f.end(), [](unsigned char c) { return std::isdigit(c); })) {
      throw std::runtime_error(where(column) + ": '" + f + "' is not a seed");
    }
    return std::stoull(f);
  }
};

ResultRow parse_row(const FieldReader& f) {
  ResultRow r;
  r.scenario = f.text(0);
  r.agent = f.text(1);
  r.think_time = f.text(2);
  r.think_time_mean_s = f.real(3, false);
  r.slice = f.text(4);
  r.seed = f.seed(5);
  r.status = f.text(6);
  r.has_episode = !f.text(7).empty();
  if (r.has_episode) {
    r.success = f.flag(7);
    r.valid = f.flag(8);
    double* pillars[] = {&r.alpha3, &r.to, &r.sp, &r.tc, &r.iq, &r.nr, &r.cc};
    for (std::size_t i = 0; i < 7; ++i) *pillars[i] = f.real(9 + i, false);
  }
  r.mission_time_s = f.real(16, true);
  r.wall_time_s = f.real(17, true);
  r.episode = f.text(18);
  if (f.fields.size() > 19) {  // tables written before the agent-fault columns have none
    r.agent_faults = f.text(19);
    if (r.has_episode && f.flag(20) != r.agent_failure()) {
      throw std::runtime_error(f.where(20) + ": disagrees with the success and agent_faults columns");
    }
  }
  return r;
}

using CellKey = std::tuple<std::string, std::string, std::string, std::string, uint64_t>;
CellKey key_of(const ResultRow& r) { return {r.scenario, r.agent, r.think_time, r.slice, r.seed}; }

}  // namespace

const std::vector<std::string>& results_columns() {
  static const std::vector<std::string> kColumns = {
      "scenario", "agent", "think_time", "think_time_mean_s", "slice", "seed", "status", "success", "valid",
      "alpha3", "TO", "SP", "TC", "IQ", "NR", "CC", "mission_time_s", "wall_time_s", "episode",
      "agent_faults", "agent_failure"};
  return kColumns;
}

void write_results_csv(const std::filesystem::path& path, const std::vector<ResultRow>& rows) {
  std::ostringstream out;
  const auto& columns = results_columns();
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << "\n";
  for (const auto& r : rows) out << row_line(r) << "\n";
  common::write_file_atomically(path, out.str());
}

std::vector<ResultRow> read_results_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot open");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(path.string() + ": empty file (expected a header line)");
  std::vector<std::string> header;
  try {
    header = common::csv_fields(line);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path.string() + ":1: " + e.what());
  }
  // A table written before the agent-fault columns (the last two) is read as it is.
  const auto& columns = results_columns();
  const bool older = header.size() == columns.size() - 2 && std::equal(header.begin(), header.end(), columns.begin());
  if (header != columns && !older) {
    std::string expected;
    for (const auto& c : results_columns()) expected += (expected.empty() ? "" : ",") + c;
    throw std::runtime_error(path.string() + ":1: not a sweep results table (expected the header " + expected + ")");
  }
  std::vector<ResultRow> rows;
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line == "\r") continue;
    std::vector<std::string> fields;
    try {
      fields = common::csv_fields(line);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(path.string() + ":" + std::to_string(line_number) + ": " + e.what());
    }
    if (fields.size() != header.size()) {
      throw std::runtime_error(path.string() + ":" + std::to_string(line_number) + ": " +
                               std::to_string(fields.size()) + " fields (expected " +
                               std::to_string(header.size()) + ")");
    }
    rows.push_back(parse_row(FieldReader{path, line_number, fields}));
  }
  return rows;
}

std::vector<std::filesystem::path> result_files(const std::filesystem::path& out_dir) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::is_directory(out_dir)) return files;
  static const std::regex kShardFile(R"(results\.shard-[0-9]+-of-[0-9]+\.csv)");
  for (const auto& entry : std::filesystem::directory_iterator(out_dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && (name == "results.csv" || std::regex_match(name, kShardFile))) {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<ResultRow> merge_result_files(const std::vector<std::filesystem::path>& files) {
  struct Kept {
    ResultRow row;
    std::filesystem::path file;
  };
  std::map<CellKey, Kept> cells;
  for (const auto& file : files) {
    for (ResultRow& row : read_results_csv(file)) {
      const CellKey key = key_of(row);
      auto it = cells.find(key);
      if (it == cells.end()) {
        cells.emplace(key, Kept{std::move(row), file});
        continue;
      }
      Kept& kept = it->second;
      if (row_line(kept.row) == row_line(row)) continue;
      if (kept.row.has_episode && row.has_episode) {
        throw std::runtime_error("cell " + row.scenario + " / " + row.agent + " / think " + row.think_time + " / " +
                                 row.slice + " / seed " + std::to_string(row.seed) + " has different results in " +
                                 kept.file.string() + " and " + file.string() +
                                 "; remove the stale file or row");
      }
      if (row.has_episode || !kept.row.has_episode) kept = Kept{std::move(row), file};
    }
  }
  std::vector<ResultRow> rows;
  for (auto& [key, kept] : cells) rows.push_back(std::move(kept.row));
  std::stable_sort(rows.begin(), rows.end(), [](const ResultRow& a, const ResultRow& b) {
    return std::tie(a.scenario, a.agent, a.think_time_mean_s, a.think_time, a.slice, a.seed) <
           std::tie(b.scenario, b.agent, b.think_time_mean_s, b.think_time, b.slice, b.seed);
  });
  return rows;
}

}  // namespace a3::rigs::sweep
