// Grouping results rows per scenario × agent × think time × slice and their statistics.
#include "rigs/sweep/aggregate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "common/atomic_file.hpp"
#include "common/csv_text.hpp"

namespace a3::rigs::sweep {
namespace {

std::optional<Interval> clamped_to_unit(std::optional<Interval> ci) {
  if (ci) ci = Interval{std::clamp(ci->lo, 0.0, 1.0), std::clamp(ci->hi, 0.0, 1.0)};
  return ci;
}

std::string number(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", x);
  return buffer;
}

std::string interval_fields(const std::optional<Interval>& ci) {
  return ci ? number(ci->lo) + "," + number(ci->hi) : std::string(",");
}

}  // namespace

std::vector<AggregateRow> aggregate(const std::vector<ResultRow>& rows) {
  using Key = std::tuple<std::string, std::string, std::string, std::string>;
  struct Group {
    AggregateRow row;
    std::vector<double> alpha3, sp, mission_time_s;
  };
  std::map<Key, std::size_t> index;
  std::vector<Group> groups;
  for (const auto& r : rows) {
    const Key key{r.scenario, r.agent, r.think_time, r.slice};
    auto [it, inserted] = index.emplace(key, groups.size());
    if (inserted) {
      Group g;
      g.row.scenario = r.scenario;
      g.row.agent = r.agent;
      g.row.think_time = r.think_time;
      g.row.think_time_mean_s = r.think_time_mean_s;
      g.row.slice = r.slice;
      groups.push_back(std::move(g));
    }
    Group& g = groups[it->second];
    if (!r.has_episode) {
      ++g.row.n_missing;
      continue;
    }
    ++g.row.n;
    g.alpha3.push_back(r.alpha3);
    g.sp.push_back(r.sp);
    if (std::isfinite(r.mission_time_s)) g.mission_time_s.push_back(r.mission_time_s);
    if (r.success) ++g.row.successes;
    if (r.agent_failure()) ++g.row.agent_failures;
  }
  std::vector<AggregateRow> out;
  for (auto& g : groups) {
    AggregateRow& a = g.row;
    a.alpha3_mean = mean_of(g.alpha3);
    a.alpha3_ci = clamped_to_unit(t_interval(g.alpha3));
    a.sp_mean = mean_of(g.sp);
    a.sp_ci = clamped_to_unit(t_interval(g.sp));
    a.mission_time_mean_s = mean_of(g.mission_time_s);
    if (a.n > 0) {
      a.success_rate = static_cast<double>(a.successes) / a.n;
      a.success_ci = wilson_interval(a.successes, a.n);
    }
    out.push_back(std::move(a));
  }
  return out;
}

void write_aggregate_csv(const std::filesystem::path& path, const std::vector<AggregateRow>& rows) {
  std::ostringstream out;
  // The interval columns are empty where the interval is undefined (t: n < 2; Wilson: n = 0).
  out << "scenario,agent,think_time,think_time_mean_s,slice,n,n_missing,alpha3_mean,alpha3_ci95_lo,"
         "alpha3_ci95_hi,SP_mean,SP_ci95_lo,SP_ci95_hi,successes,success_rate,success_ci95_lo,success_ci95_hi,"
         "mission_time_mean_s,agent_failures\n";
  for (const auto& a : rows) {
    out << common::csv_cell(a.scenario) << "," << common::csv_cell(a.agent) << "," << common::csv_cell(a.think_time) << ","
        << number(a.think_time_mean_s) << "," << common::csv_cell(a.slice) << "," << a.n << "," << a.n_missing << ","
        << (a.n ? number(a.alpha3_mean) : "") << "," << interval_fields(a.alpha3_ci) << ","
        << (a.n ? number(a.sp_mean) : "") << "," << interval_fields(a.sp_ci) << "," << a.successes << ","
        << (a.n ? number(a.success_rate) : "") << "," << interval_fields(a.success_ci) << ","
        << (a.n ? number(a.mission_time_mean_s) : "") << "," << a.agent_failures << "\n";
  }
  common::write_file_atomically(path, out.str());
}

}  // namespace a3::rigs::sweep
