// The episode file (α³-Bench format, SPEC §1) from what the recorder saw: the initial state as
// the rig started, the dialogue, the final state (the true final pose and battery, the safety
// flags set by any measured no-fly-zone intrusion or separation breach), success (the
// mission's objectives met, no crash), _meta as the public corpus writes it, and _rig with
// what only the rig knows. Plus the trajectory plot.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "rigs/run/episode_recorder.hpp"
#include "rigs/run/run_options.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

struct RunFacts {
  std::string status;            // completed | time_limit | crashed | interrupted | node_failed: ...
  std::string agent_name;
  double mission_time_s = 0.0;
  double wall_time_s = 0.0;
  double achieved_real_time_factor = 0.0;
  int64_t start_unix_us = 0;
  nlohmann::json counters = nlohmann::json::object();
  nlohmann::json realtime;       // real time: rigs/run/realtime_report.hpp (null in virtual time)
};

nlohmann::json build_episode(const Scenario& scenario, const RunOptions& options, const RecordedEpisode& rec,
                             const RunFacts& facts);

// Writes DIR/episode.json whole or not at all (creating DIR); throws common::OutputError
// ("<file>: <reason>") when it cannot. Text that is not UTF-8 is replaced, never thrown about.
void write_episode(const std::filesystem::path& dir, const nlohmann::json& episode);
// DIR/trajectory.png (gnuplot): the ground track over the geofence, no-fly zones and
// objectives, and altitude and battery over time, with its data and script (trajectory.tsv,
// trajectory.gp). Returns "" when written, or why gnuplot could not draw it; throws
// common::OutputError ("<file>: <reason>") when a file could not be written whole (a full disk).
std::string write_trajectory_plot(const std::filesystem::path& dir, const Scenario& scenario,
                                  const RecordedEpisode& rec);

}  // namespace a3::rigs
