// Whether a sweep cell is done, and its row of results.csv. A cell is complete when its
// episode.json parses, belongs to the cell (agent, think time, seed) and ended the way an episode
// ends (completed, time_limit, crashed); an interrupted run, a failed node, a broken real-time
// contract (realtime_violated: the host, not the agent, decided the outcome), an agent that never
// acted (agent_failed) or an endpoint that failed (endpoint_failed), a half-written or missing
// file leaves the cell incomplete, and a resumed sweep runs it again.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "rigs/sweep/results_table.hpp"
#include "rigs/sweep/sweep_grid.hpp"

namespace a3::rigs::sweep {

struct CellCheck {
  bool complete = false;
  std::string why_not;  // when incomplete
  bool realtime_violated = false;  // the run broke the real-time contract: worth another try
  nlohmann::json episode;
};

CellCheck check_cell(const std::filesystem::path& dir, const SweepCell& cell);

// Scores episodes as `a3rig score` does. Not thread-safe: one per thread.
class EpisodeScorer {
 public:
  EpisodeScorer();
  ~EpisodeScorer();
  EpisodeScorer(const EpisodeScorer&) = delete;
  EpisodeScorer& operator=(const EpisodeScorer&) = delete;

  // The row of a complete cell; `episode_relative` is written in the row's episode column.
  ResultRow row(const SweepCell& cell, const nlohmann::json& episode, const std::string& episode_relative);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The row of a cell without a complete episode, e.g. status "failed: <why>".
ResultRow row_without_episode(const SweepCell& cell, const std::string& status);

}  // namespace a3::rigs::sweep
