// The flags a run's options come from, each named once: `a3rig run` and `a3rig mcp` add them
// (rigs/cli/run_flag_options.hpp parses each into its typed RunOptions field), `a3rig node part`
// adds the ones a part needs, and the runs a3rig starts itself write them back with to_argv:
// `--processes` children (`a3rig node part`) and a sweep's cells (`a3rig run`).
#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "rigs/run/run_options.hpp"

namespace a3::rigs {

enum class RunFlag {
  kScenario, kAgent, kThinkTime, kRuntime, kSlice, kSeed, kOut, kRtf, kSync, kLcmUrl, kCan, kIntegrator,
  kDynamicsRate, kSharedDir, kMaxTurns, kMinTurns, kNoLcmLog, kNoPlot, kNoReport, kQuiet
};

// "--scenario", "--no-lcm-log", ...
const char* flag_name(RunFlag flag);
// The flags as a command line gives them, in the order asked for. A flag whose option is unset
// (no slice override) is left out; a switch (--no-plot, --quiet) is written when it is on.
std::vector<std::string> to_argv(const RunOptions& options, std::initializer_list<RunFlag> flags);

}  // namespace a3::rigs
