// How long a sweep will take, said before it starts (issue 34: a sweep's size surprises people
// by the default axes). Virtual time: a measured cost per cell for a scripted or replayed agent
// (an LLM agent's cells take as long as its endpoint answers). Real time: an upper bound, each
// cell at most its mission's time limit divided by the real-time factor.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "rigs/sweep/sweep_grid.hpp"

namespace a3::rigs::sweep {

// Wall seconds a virtual-time cell of the scripted agent takes, one job per core: a sweep of
// generated missions measured 2.2 episodes/s with 2 jobs on the 2-core host (docs/sweep.md),
// 0.9 s a cell and job; the built-in missions are shorter (7.2 episodes/s).
constexpr double kVirtualCellWall_s = 0.9;

struct SweepEstimate {
  double wall_s = 0.0;
  bool upper_bound = false;    // real time: cells end when their mission does, often sooner
  bool has_llm_cells = false;  // their cost is the endpoint's, not counted
};

// cells: those to run; time_limit_s: each scenario's mission time limit (real time).
SweepEstimate estimate_sweep(const std::vector<SweepCell>& cells, const std::string& runtime,
                             double real_time_factor, int jobs, const std::map<std::string, double>& time_limit_s);

// "about 4 min (virtual time: ~1.8 s a cell with the scripted agent)", for the sweep's header.
std::string estimate_text(const SweepEstimate& estimate, std::size_t cells, double real_time_factor);

// "42 s", "4.2 min", "2.5 h".
std::string duration_text(double seconds);

}  // namespace a3::rigs::sweep
