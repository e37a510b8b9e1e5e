// The options of a flown episode that `a3rig run` and `a3rig mcp` share (scenario, runtime,
// pace, output, seed, think time, turns, network, real-time plumbing), defined once.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "rigs/core/run_options.hpp"

namespace a3::rigs {

// Where the flags write: the options, and the two that need converting after parsing.
struct ScenarioRunFlags {
  RunOptions options;
  std::string runtime = "real";  // real | virtual
  std::string out;               // "" keeps options.out_dir
  // Applies runtime and out to options; throws std::invalid_argument for a bad combination.
  void apply();
};

void add_scenario_run_flags(CLI::App& cmd, ScenarioRunFlags& flags);

}  // namespace a3::rigs
