// The orchestrator behind `a3rig run`: builds every node of the rig from a scenario — dynamics,
// bridge, flight controller (over CAN), link emulator, tool server, airspace monitor, the
// conversation with its agent, and the recorders — runs them in virtual time (one thread,
// the discrete-event scheduler, a simulated CAN bus) or in real time (a thread per node, LCM
// over UDP multicast, a CAN bus of its own), supervises them, and ends the episode when the
// dialogue is over and the vehicle has landed, at the mission's time limit, on a crash, on
// Ctrl-C, or when a node fails — writing the episode whatever happened.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rigs/run/run_options.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

struct RunResult {
  std::string status;
  std::string flight_status;  // how the flight ended; status differs when an output was lost
  nlohmann::json episode;
  std::filesystem::path episode_path;  // empty when episode.json could not be written
  std::string plot_problem;  // "" when the plot was written
  std::string report_problem;  // "" when report.html was written
  std::vector<std::string> outputs_lost;  // "<file>: <reason>" of every output that could not be written
  double mission_time_s = 0.0;
  double wall_time_s = 0.0;
  double achieved_real_time_factor = 0.0;
};

using ProgressFn = std::function<void(const std::string& line)>;

// The exit status of `a3rig run` for a run's status: 0 written, 3 interrupted, 4 node_failed,
// 5 realtime_violated, 6 agent_failed, 7 endpoint_failed (rigs/run/agent_outcome.hpp),
// 8 output_failed (an output could not be written: rigs/outputs/run_outputs.hpp), 9 never_flew
// (the vehicle never left the ground on a mission with objectives: rigs/run/agent_outcome.hpp).
int run_exit_status(const std::string& status);

// stop: set from a signal handler to end the run early (the episode is still written).
// Throws OutputSpaceError before take-off when the output folder has too little room.
RunResult run_episode(const Scenario& scenario, const RunOptions& options, const ProgressFn& progress,
                      const std::atomic<bool>* stop);

}  // namespace a3::rigs
