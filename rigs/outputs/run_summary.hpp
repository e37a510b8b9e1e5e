// The closing lines of a run (`a3rig run`, `a3rig mcp`): where the episode, LCM log and plot
// were written (or "not written (<file>: <reason>)"), the status (with how the flight ended
// when an output was lost: `output_failed: ...`, exit 8) and timing, the real-time accounting,
// success, and the α³ score of the episode as `a3rig score` computes it (or why the episode
// is not valid). `a3rig mcp` prints them on stderr, since its stdout carries the MCP session.
#pragma once

#include <cstdio>

#include "rigs/run/rig_runner.hpp"
#include "rigs/run/run_options.hpp"

namespace a3::rigs {

void print_run_summary(std::FILE* out, const RunResult& result, const RunOptions& options);

}  // namespace a3::rigs
