// Leaderboard writers.
#include "eval/leaderboard_format.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "common/csv_text.hpp"
#include "common/json_text.hpp"

namespace a3::eval {
namespace {

std::string fixed5(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.5f", x);
  return buffer;
}

std::string pillars_json(const PillarMeans& p) {
  return "{\"TO\":" + format_double(p.to) + ",\"SP\":" + format_double(p.sp) +
         ",\"TC\":" + format_double(p.tc) + ",\"IQ\":" + format_double(p.iq) +
         ",\"NR\":" + format_double(p.nr) + ",\"CC\":" + format_double(p.cc) + "}";
}

std::string pillars_short(const PillarMeans& p) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "TO %.3f SP %.3f TC %.3f IQ %.3f NR %.3f CC %.3f", p.to,
                p.sp, p.tc, p.iq, p.nr, p.cc);
  return buffer;
}

// The row's cells in column order; `exact` chooses full precision over 5 decimals.
std::vector<std::string> cells(const ModelSummary& r, bool exact) {
  auto num = [&](double x) { return exact ? format_double(x) : fixed5(x); };
  return {r.model,
          r.domain,
          num(r.mean),
          num(r.ci95),
          std::to_string(r.n),
          num(r.success_rate),
          num(r.gen_fail_rate),
          num(r.reliability),
          num(r.coverage),
          num(r.alpha3_rel),
          exact ? pillars_json(r.pillars) : pillars_short(r.pillars),
          num(r.mean_gen_time_s),
          num(r.mean_total_tokens),
          num(r.alpha3_per_second),
          num(r.alpha3_per_1k_tokens),
          std::to_string(r.total_attempt_calls),
          num(r.mean_attempts_used),
          num(r.call_efficiency)};
}

nlohmann::ordered_json row_json(const ModelSummary& r) {
  nlohmann::ordered_json j;
  j["model"] = r.model;
  j["domain"] = r.domain;
  j["mean"] = r.mean;
  j["ci95"] = r.ci95;
  j["n"] = r.n;
  j["success_rate"] = r.success_rate;
  j["gen_fail_rate"] = r.gen_fail_rate;
  j["reliability"] = r.reliability;
  j["coverage"] = r.coverage;
  j["alpha3_rel"] = r.alpha3_rel;
  j["pillars"] = {{"TO", r.pillars.to}, {"SP", r.pillars.sp}, {"TC", r.pillars.tc},
                  {"IQ", r.pillars.iq}, {"NR", r.pillars.nr}, {"CC", r.pillars.cc}};
  j["mean_gen_time_s"] = r.mean_gen_time_s;
  j["mean_total_tokens"] = r.mean_total_tokens;
  j["alpha3_per_second"] = r.alpha3_per_second;
  j["alpha3_per_1k_tokens"] = r.alpha3_per_1k_tokens;
  j["total_attempt_calls"] = r.total_attempt_calls;
  j["mean_attempts_used"] = r.mean_attempts_used;
  j["call_efficiency"] = r.call_efficiency;
  j["files"] = r.files;
  j["n_fail"] = r.n_fail;
  j["n_invalid"] = r.n_invalid;
  j["budget"] = r.budget;
  return j;
}

}  // namespace

std::string format_double(double x) {
  if (!std::isfinite(x)) return "null";
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  if (ec != std::errc()) return "null";
  return std::string(buffer, end);
}

LeaderboardFormat parse_leaderboard_format(std::string_view name) {
  if (name == "table") return LeaderboardFormat::kTable;
  if (name == "csv") return LeaderboardFormat::kCsv;
  if (name == "json") return LeaderboardFormat::kJson;
  if (name == "markdown" || name == "md") return LeaderboardFormat::kMarkdown;
  throw std::invalid_argument("unknown leaderboard format '" + std::string(name) +
                              "' (known: table, csv, json, markdown)");
}

const std::vector<std::string>& leaderboard_columns() {
  static const std::vector<std::string> kColumns = {
      "model", "domain", "mean", "ci95", "n", "success_rate", "gen_fail_rate", "reliability",
      "coverage", "alpha3_rel", "pillars", "mean_gen_time_s", "mean_total_tokens",
      "alpha3_per_second", "alpha3_per_1k_tokens", "total_attempt_calls", "mean_attempts_used",
      "call_efficiency"};
  return kColumns;
}

void write_leaderboard(std::ostream& out, const std::vector<ModelSummary>& rows,
                       LeaderboardFormat format) {
  const auto& columns = leaderboard_columns();
  switch (format) {
    case LeaderboardFormat::kCsv: {
      for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
      out << "\n";
      for (const auto& row : rows) {
        const auto values = cells(row, true);
        for (std::size_t c = 0; c < values.size(); ++c) out << (c ? "," : "") << common::csv_cell(values[c]);
        out << "\n";
      }
      return;
    }
    case LeaderboardFormat::kJson: {
      nlohmann::ordered_json array = nlohmann::ordered_json::array();
      for (const auto& row : rows) array.push_back(row_json(row));
      out << common::dump_json_text(array, 2) << "\n";  // model names come from folder names
      return;
    }
    case LeaderboardFormat::kMarkdown: {
      out << "|";
      for (const auto& c : columns) out << " " << c << " |";
      out << "\n|";
      for (std::size_t c = 0; c < columns.size(); ++c) out << (c < 2 ? " --- |" : " ---: |");
      out << "\n";
      for (const auto& row : rows) {
        out << "|";
        for (const auto& v : cells(row, false)) out << " " << v << " |";
        out << "\n";
      }
      return;
    }
    case LeaderboardFormat::kTable: {
      std::vector<std::vector<std::string>> table{columns};
      for (const auto& row : rows) table.push_back(cells(row, false));
      std::vector<std::size_t> width(columns.size(), 0);
      for (const auto& line : table) {
        for (std::size_t c = 0; c < line.size(); ++c) width[c] = std::max(width[c], line[c].size());
      }
      for (const auto& line : table) {
        std::string text;
        for (std::size_t c = 0; c < line.size(); ++c) {
          const std::size_t pad = width[c] - line[c].size();
          const bool left = c < 2 || c == 10;
          if (c) text += "  ";
          text += left ? line[c] + std::string(pad, ' ') : std::string(pad, ' ') + line[c];
        }
        while (!text.empty() && text.back() == ' ') text.pop_back();
        out << text << "\n";
      }
      return;
    }
  }
}

}  // namespace a3::eval
