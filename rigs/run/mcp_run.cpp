// Running an episode for an MCP client.
#include "rigs/run/mcp_run.hpp"

#include "agent/conversation/think_time.hpp"

namespace a3::rigs {

std::unique_ptr<agent::mcp::McpAgent> make_mcp_agent(const Scenario& s, const RunOptions& o, std::atomic<bool>* stop) {
  agent::mcp::McpMissionBrief brief;
  brief.scenario = s.name;
  brief.mission = s.mission;
  brief.initial_state = s.initial_state;
  brief.airspace = s.airspace_brief();
  brief.min_turns = o.min_turns;
  brief.max_turns = o.max_turns;
  agent::mcp::McpAgentOptions options;
  options.charge_wall_time = agent::ThinkTime::parse(o.think_time).is_zero();
  options.stop = stop;
#ifdef A3RIG_VERSION
  options.server_version = A3RIG_VERSION;
#endif
  return std::make_unique<agent::mcp::McpAgent>(std::move(brief), options);
}

RunResult run_mcp_episode(const Scenario& s, RunOptions o, agent::mcp::McpAgent& agent, const ProgressFn& progress,
                          const std::atomic<bool>* stop) {
  o.agent = "mcp";
  o.agent_factory = [&agent] { return agent.borrow(); };
  RunResult r;
  try {
    r = run_episode(s, o, progress, stop);
  } catch (...) {
    agent.set_episode_over("node_failed", o.out_dir / "episode.json");
    throw;
  }
  agent.set_episode_over(r.status, r.episode_path);
  return r;
}

}  // namespace a3::rigs
