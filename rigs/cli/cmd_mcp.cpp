// `a3rig mcp`: the live rig as an MCP server. The rig flies the scenario without a built-in
// agent; an MCP client (stdio by default, or Streamable HTTP with --http) is the agent: its
// tool calls are the agent's actions, report_turn ends its turns. The episode is written and
// scored as `a3rig run` does, with the closing lines on stderr (stdout carries the session).
#include <CLI/CLI.hpp>

#include <atomic>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "agent/mcp/mcp_server.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/http_limit_flags.hpp"
#include "rigs/cli/scenario_run_flags.hpp"
#include "rigs/cli/signal_stop.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/outputs/run_outputs.hpp"
#include "rigs/outputs/run_summary.hpp"
#include "rigs/run/mcp_run.hpp"
#include "rigs/scenario/shared_dir.hpp"

namespace a3::rigs {
namespace {

struct McpArgs {
  ScenarioRunFlags flags;
  std::string http;  // "" : stdio; else HOST:PORT
  agent::http::HttpLimits http_limits;
  agent::http::OriginPolicy http_origins;
  std::vector<CLI::Option*> http_limit_flags;
};

// "127.0.0.1:8765" -> host, port (0: any free port). Throws naming the bad part.
void parse_http(const std::string& spec, agent::mcp::McpServerOptions& out) {
  const auto colon = spec.rfind(':');
  if (colon == std::string::npos || colon == 0) {
    throw std::invalid_argument("--http: expected HOST:PORT (e.g. 127.0.0.1:8765), got '" + spec + "'");
  }
  out.http_host = spec.substr(0, colon);
  try {
    std::size_t used = 0;
    out.http_port = std::stoi(spec.substr(colon + 1), &used);
    if (used != spec.size() - colon - 1 || out.http_port < 0 || out.http_port > 65535) throw std::out_of_range("");
  } catch (const std::exception&) {
    throw std::invalid_argument("--http: the port must be 0..65535, got '" + spec.substr(colon + 1) + "'");
  }
}

void to_stderr(const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); }

// The episode on a thread of its own: run, score on stderr, and (after Ctrl-C) end the session.
struct EpisodeThread {
  std::thread thread;
  std::string status = "node_failed";
  std::exception_ptr failure;
  void start(const Scenario& s, const RunOptions& o, agent::mcp::McpAgent& agent, agent::mcp::McpServer& server,
             std::atomic<bool>& stop) {
    thread = std::thread([this, &s, o, &agent, &server, &stop] {
      try {
        const ProgressFn print = [&o](const std::string& line) {
          if (!o.quiet) to_stderr(line);
        };
        const RunResult r = run_mcp_episode(s, o, agent, print, &stop);
        print_run_summary(stderr, r, o);
        if (!agent.client_gone()) {
          to_stderr("a3rig mcp: the episode is written; calls now answer with its status until the client leaves");
        }
        status = r.status;
      } catch (...) {
        failure = std::current_exception();
      }
      if (stop_requested() || failure) server.stop();
    });
  }
};

int serve(McpArgs& a) {
  a.flags.apply();
  RunOptions& o = a.flags.options;
  o.shared_dir = default_shared_dir();
  const Scenario scenario = load_scenario_spec(o.scenario, o.shared_dir);
  check_output_space(scenario, o);  // before any session: a client never flies a run that cannot be written
  std::atomic<bool> stop{false};
  auto agent = make_mcp_agent(scenario, o, &stop);
  agent::mcp::McpServerOptions server_options;
  server_options.log = to_stderr;
  if (!a.http.empty()) parse_http(a.http, server_options);
  for (const CLI::Option* flag : a.http_limit_flags) {
    if (flag->count() > 0 && a.http.empty()) throw std::invalid_argument(flag->get_name() + ": applies to --http only");
  }
  server_options.http_limits = a.http_limits;
  server_options.http_origins = a.http_origins;
  agent::mcp::McpServer server(*agent, server_options);
  to_stderr("a3rig mcp: scenario " + scenario.name + " (" + scenario.source + "), think time " + o.think_time + ", " +
            (o.runtime == Runtime::kVirtual ? "virtual time" : "real time") + ", seed " + std::to_string(o.seed) +
            ", output " + o.out_dir.string());
  to_stderr("mission: " + scenario.mission.description);
  const StopWatcher watcher(stop);
  EpisodeThread episode;
  episode.start(scenario, o, *agent, server, stop);
  try {
    if (a.http.empty()) {
      to_stderr("a3rig mcp: serving MCP on stdio");
      server.serve_stdio(std::cin, std::cout);
    } else {
      const int port = server.start_http();
      to_stderr("a3rig mcp: serving MCP (Streamable HTTP) at http://" + server_options.http_host + ":" +
                std::to_string(port) + server_options.http_path);
      server.wait_http();
    }
  } catch (...) {
    stop = true;
    episode.thread.join();
    throw;
  }
  agent->client_closed();
  episode.thread.join();
  if (episode.failure) std::rethrow_exception(episode.failure);
  return run_exit_status(episode.status);
}

}  // namespace

A3_REGISTER_COMMAND("12-mcp", [](CLI::App& app) {
  auto args = std::make_shared<McpArgs>();
  CLI::App* cmd = app.add_subcommand(
      "mcp",
      "Serve the live rig to an MCP client (Model Context Protocol 2025-06-18; 2025-03-26 accepted): the rig flies "
      "the scenario and the client is its agent. tools/list is the tool registry (the vehicle's tools, the peers' "
      "A2A tasks as a2a_<task>, and report_turn); each tools/call crosses the emulated 6G link both ways and "
      "executes on the vehicle, its result is the observation (isError for refusals by the safety gate, errors, "
      "timeouts and bad arguments); report_turn {intent, text} ends the agent's turn and returns the supervisor's "
      "reply (the next turn; dialogue_over when the dialogue has ended). The mission brief is the server's "
      "instructions and the resource a3rig://mission; the dialogue so far is a3rig://dialogue. Long waits send "
      "progress notifications about once a second.\n"
      "Transport: stdio (default; stdout carries only the session, everything else goes to stderr) or Streamable "
      "HTTP with --http HOST:PORT (endpoint /mcp; loopback by default; port 0 picks a free one, printed on "
      "stderr).\n"
      "Time: in real time the client's own time between calls passes in the simulated world; in virtual time the "
      "simulation waits for the client, and each call is charged the client's measured wall time since the "
      "previous result (or, with --think-time, that model instead).\n"
      "The session ends when the client leaves (stdin closed, or the HTTP session deleted): mid-dialogue the run "
      "stops and the episode is written with status interrupted; after the dialogue the vehicle lands and the "
      "episode is written as usual. When the turn budget is spent, calls answer that the dialogue is over; once "
      "the episode is written (and scored, on stderr), calls answer isError naming its status and file until the "
      "client leaves, and then a3rig mcp exits. Ctrl-C stops the run, writes the episode and ends the session.\n"
      "Exit status (as a3rig run): 0 the episode was written, 2 bad usage or input, 3 interrupted (the client left "
      "mid-dialogue, or Ctrl-C; episode written), 4 a node failed or froze (episode written), 5 the real-time "
      "contract was broken (episode written), 6 the client never made a vehicle or A2A call (status agent_failed; "
      "episode written), 8 an output could not be written (status output_failed: <file>: <reason>), 9 the vehicle "
      "never left the ground on a mission with objectives (status never_flew; episode written).");
  add_scenario_run_flags(*cmd, args->flags);
  cmd->add_option("--http", args->http,
                  "serve Streamable HTTP on HOST:PORT (e.g. 127.0.0.1:8765; endpoint /mcp) instead of stdio; a POST "
                  "without Content-Length is a 411, a malformed one a 400, one over 8 MiB a 413, a request whose head "
                  "or body comes too late a 408, a connection beyond --max-connections a 503 (JSON-RPC errors; "
                  "--max-connections, --header-timeout and --body-timeout apply with --http only)");
  args->http_limit_flags = add_http_limit_flags(*cmd, args->http_limits);
  for (CLI::Option* flag : add_http_origin_flags(*cmd, args->http_origins)) args->http_limit_flags.push_back(flag);
  cmd->callback([args] { command_exit_status() = serve(*args); });
});

}  // namespace a3::rigs
