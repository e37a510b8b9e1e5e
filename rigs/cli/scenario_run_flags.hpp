// The options of a flown episode that `a3rig run` and `a3rig mcp` share (scenario, runtime,
// pace, output, seed, think time, turns, network, real-time plumbing), defined once.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "rigs/run/run_options.hpp"

namespace a3::rigs {

// Where the flags write: the options (rigs/cli/run_flag_options.hpp parses each into its field).
struct ScenarioRunFlags {
  RunOptions options;
  // Checks what no single flag can (--processes with virtual time, memq:// in real time) and
  // sets the log level for -q; throws std::invalid_argument for a bad combination.
  void apply();
};

void add_scenario_run_flags(CLI::App& cmd, ScenarioRunFlags& flags);

}  // namespace a3::rigs
