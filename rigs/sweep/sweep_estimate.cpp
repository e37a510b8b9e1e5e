// The sweep's time, estimated.
#include "rigs/sweep/sweep_estimate.hpp"

#include <algorithm>
#include <cstdio>

namespace a3::rigs::sweep {

SweepEstimate estimate_sweep(const std::vector<SweepCell>& cells, const std::string& runtime,
                             double real_time_factor, int jobs, const std::map<std::string, double>& time_limit_s) {
  SweepEstimate e;
  double total_s = 0.0;
  for (const SweepCell& cell : cells) {
    if (cell.agent == "llm") e.has_llm_cells = true;
    if (runtime == "virtual") {
      total_s += kVirtualCellWall_s;
      continue;
    }
    const auto limit = time_limit_s.find(cell.scenario);
    total_s += (limit == time_limit_s.end() ? 900.0 : limit->second) / std::max(real_time_factor, 1e-3);
    e.upper_bound = true;
  }
  // Real-time cells each want a core to themselves; virtual ones share them, jobs at a time.
  e.wall_s = total_s / std::max(jobs, 1);
  return e;
}

std::string duration_text(double seconds) {
  char text[32];
  if (seconds < 90.0) {
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  } else if (seconds < 5400.0) {
    std::snprintf(text, sizeof text, "%.1f min", seconds / 60.0);
  } else {
    std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
  }
  return text;
}

std::string estimate_text(const SweepEstimate& e, std::size_t cells, double real_time_factor) {
  if (cells == 0) return "nothing to run";
  std::string text = (e.upper_bound ? "at most " : "about ") + duration_text(e.wall_s);
  char why[200];
  if (e.upper_bound) {
    std::snprintf(why, sizeof why, " (real time: each cell at most its mission's time limit / rtf %g)", real_time_factor);
  } else {
    std::snprintf(why, sizeof why, " (virtual time: ~%.1f s a cell with the scripted agent)", kVirtualCellWall_s);
  }
  text += why;
  if (e.has_llm_cells) text += ", plus the LLM endpoint's answering time";
  return text;
}

}  // namespace a3::rigs::sweep
