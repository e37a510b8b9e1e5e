// The rig behind `a3rig mcp`: an episode whose agent is an MCP client's session (McpAgent).
// make_mcp_agent() briefs the agent from the scenario; run_mcp_episode() runs the episode with
// it (RunOptions::agent_factory, agent "mcp") and, once the episode is written, tells the agent
// (its calls then answer with the status and the file). The caller serves MCP meanwhile.
#pragma once

#include <atomic>
#include <memory>

#include "agent/mcp/mcp_agent.hpp"
#include "rigs/run/rig_runner.hpp"
#include "rigs/run/run_options.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

// The agent for a run of `scenario` with `options`. In virtual time each step is charged the
// client's wall time, unless options.think_time gives a model (then that is charged instead).
// `stop` is the run's stop flag (set when the client leaves mid-dialogue). Throws
// std::invalid_argument for a bad think time.
std::unique_ptr<agent::mcp::McpAgent> make_mcp_agent(const Scenario& scenario, const RunOptions& options,
                                                     std::atomic<bool>* stop);

// Runs the episode with `agent` (which outlives the run) and marks the agent's episode over.
RunResult run_mcp_episode(const Scenario& scenario, RunOptions options, agent::mcp::McpAgent& agent,
                          const ProgressFn& progress, const std::atomic<bool>* stop);

}  // namespace a3::rigs
