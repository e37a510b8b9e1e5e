// `a3rig run`: flies one conversational mission on the rig and writes the episode.
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/run_flag_options.hpp"
#include "rigs/cli/scenario_run_flags.hpp"
#include "rigs/cli/signal_stop.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/outputs/run_summary.hpp"
#include "rigs/run/llm_run.hpp"
#include "rigs/run/node_configs.hpp"
#include "rigs/run/rig_runner.hpp"
#include "rigs/scenario/shared_dir.hpp"

namespace a3::rigs {
namespace {

int run(ScenarioRunFlags& args) {
  args.apply();
  RunOptions& o = args.options;
  o.shared_dir = default_shared_dir();
  const Scenario scenario = load_scenario_spec(o.scenario, o.shared_dir);
  make_agent(o);  // a bad agent, think time or LLM endpoint is a usage error before anything is written
  auto print = [&](const std::string& line) {
    if (!o.quiet) std::fprintf(stderr, "%s\n", line.c_str());
  };
  if (o.agent == "llm" && !o.agent_factory) {
    try {
      check_llm_endpoint(llm_endpoint(o));
    } catch (const EndpointUnreachable& e) {
      std::fprintf(stderr, "a3rig run: %s\na3rig run: nothing flew, no episode written (status endpoint_failed)\n",
                   e.what());
      return run_exit_status("endpoint_failed");
    }
  }
  print("a3rig run: scenario " + scenario.name + " (" + scenario.source + "), agent " + o.agent + ", think time " +
        o.think_time + ", " + (o.runtime == Runtime::kVirtual ? "virtual time" : "real time") + ", seed " +
        std::to_string(o.seed) + ", output " + o.out_dir.string());
  print("mission: " + scenario.mission.description);
  std::atomic<bool> stop{false};
  RunResult r;
  {
    const StopWatcher watcher(stop);
    r = run_episode(scenario, o, print, &stop);
  }
  print_run_summary(stdout, r, o);
  return run_exit_status(r.status);
}

}  // namespace

A3_REGISTER_COMMAND("10-run", [](CLI::App& app) {
  auto args = std::make_shared<ScenarioRunFlags>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Fly one conversational mission on the rig: the agent and the simulated supervisor alternate turns, the "
      "agent's tool calls cross the emulated 6G link to the vehicle, the flight controller flies over CAN, and the "
      "episode is written (episode.json in the α³-Bench format, an LCM log, a trajectory plot) and scored. Exit "
      "status: 0 the episode was written, 2 bad usage or input, 3 interrupted (episode written), 4 a node failed "
      "or froze (episode written), 5 the real-time contract was broken (status realtime_violated: the host could "
      "not keep the requested pace; episode written with its accounting in _rig.realtime), 6 the agent never "
      "produced a valid action (status agent_failed: no agent turn carried an action; episode written with each "
      "turn's error), 7 the LLM endpoint failed (status endpoint_failed: --agent llm checks it with one short call "
      "before take-off and exits 7 at once, writing nothing, when it does not answer; during the run, 2 agent turns "
      "in a row whose calls failed at the HTTP/network level, after the client's retries, end the run at once, "
      "episode written), 8 an output could not be written (status output_failed: <file>: <reason>, e.g. No space "
      "left on device; the closing lines name every file not written; a run that ended otherwise, e.g. "
      "interrupted, keeps its status and exit status and names the lost files beside it), 9 the vehicle never left "
      "the ground on a mission with objectives (status never_flew; episode written).\n"
      "Before take-off the free space of --out is checked against the run's largest outputs (episode, LCM log, "
      "plot; from the mission's time limit): too little refuses to fly (exit 2, nothing written) unless "
      "A3_SKIP_SPACE_CHECK=1. Every file is written to a temporary name and renamed when whole.\n"
      "Real time: by default the vehicle's nodes run in lockstep (--sync lockstep): simulated time never passes a "
      "flight-controller step that has not been computed, so a loaded host slows simulated time down instead of "
      "breaking the physics; --sync free runs every node on the wall clock (for a real flight controller on a real "
      "CAN bus), where lateness is measured and reported.\n"
      "--agent llm asks an OpenAI-compatible endpoint (hosted API, OpenRouter, vLLM, llama.cpp, Ollama, or "
      "`a3rig serve-model`) for every agent turn; its API key is read only from the environment, never from the "
      "command line: A3_LLM_API_KEY, else the first line of the file named by A3_LLM_API_KEY_FILE, else "
      "OPENAI_API_KEY (none: no Authorization header, for local servers). A3_LLM_BASE_URL and A3_LLM_MODEL "
      "give --llm-base-url and --llm-model when those are not given; A3_LLM_PROVIDER names the provider in the "
      "episode's _meta (default: from the URL).");
  RunOptions& o = args->options;
  add_scenario_run_flags(*cmd, *args);
  add_run_flag(*cmd, o, RunFlag::kAgent);
  cmd->add_option("--llm-base-url", o.llm_base_url,
                  "--agent llm: the endpoint, e.g. https://api.openai.com/v1, https://openrouter.ai/api/v1, "
                  "http://127.0.0.1:8088/v1 (default $A3_LLM_BASE_URL)");
  cmd->add_option("--llm-model", o.llm_model,
                  "--agent llm: the model, e.g. gpt-4.1-mini, anthropic/claude-haiku-4.5 (default $A3_LLM_MODEL)");
  cmd->add_option("--llm-max-tokens", o.llm_max_tokens, "--agent llm: completion tokens per call (default 2048)")
      ->check(a3::rigs::between(1, 1000000));
  cmd->add_option("--llm-timeout", o.llm_timeout_s,
                  "--agent llm: seconds one HTTP attempt may take (default 180); in real time the world flies on "
                  "meanwhile")
      ->check(a3::rigs::positive());
  cmd->add_option("--llm-tools", o.llm_tools,
                  "--agent llm: native (default: every MCP tool and A2A task is an OpenAI function, the model's "
                  "tool_calls are the turn's actions and its report_turn call the turn's intent and text; without "
                  "report_turn the intent is the first call's function name and the text the message's content) or "
                  "json (the α³-Bench paper's protocol: a JSON object {intent, text, actions} in the reply's text)")
      ->check(CLI::IsMember({"native", "json"}));
  cmd->add_option("--llm-retries", o.llm_retries,
                  "--agent llm: HTTP retries of one call on 429/5xx and network errors, with backoff (default 4); "
                  "each of a turn's up to 3 attempts makes them")
      ->check(a3::rigs::between(0, 100));
  cmd->add_flag("--llm-stream", o.llm_stream,
                "--agent llm: stream the answers (stream: true, server-sent events); each attempt's time to the first "
                "and to the last token goes into the turn's _rig.attempt_log (ttft_s, ttlt_s)");
  cmd->add_flag("--processes", o.processes,
                "real time: run dynamics, bridge, fc, linkemu and the vehicle side as processes of their own "
                "(`a3rig node part NAME`), talking only LCM and CAN; a process that dies ends the run (status 4)");
  cmd->callback([args] { command_exit_status() = run(*args); });
});

}  // namespace a3::rigs
