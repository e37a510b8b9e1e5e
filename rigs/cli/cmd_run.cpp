// `a3rig run`: flies one conversational mission on the rig and writes the episode.
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/pillars.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/signal_stop.hpp"
#include "rigs/core/node_configs.hpp"
#include "rigs/core/llm_run.hpp"
#include "rigs/core/realtime_report.hpp"
#include "rigs/core/rig_runner.hpp"
#include "rigs/core/shared_dir.hpp"

namespace a3::rigs {
namespace {

struct RunArgs {
  RunOptions options;
  std::string runtime = "real";
  std::string out;
};

std::atomic<bool>& stop_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

int run(RunArgs& args) {
  RunOptions& o = args.options;
  o.runtime = args.runtime == "virtual" ? Runtime::kVirtual : Runtime::kReal;
  if (!args.out.empty()) o.out_dir = args.out;
  if (o.processes && o.runtime == Runtime::kVirtual) {
    throw std::invalid_argument("--processes: runs in real time only (virtual time is one process by design); drop "
                                "--runtime virtual or --processes");
  }
  o.shared_dir = default_shared_dir();
  const Scenario scenario = load_scenario(o.scenario, o.shared_dir);
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
  install_stop_signals();
  std::thread watcher([] {
    while (!stop_flag()) {
      if (stop_requested()) stop_flag() = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  RunResult r;
  try {
    r = run_episode(scenario, o, print, &stop_flag());
  } catch (...) {
    stop_flag() = true;
    watcher.join();
    throw;
  }
  stop_flag() = true;
  watcher.join();

  // Score the episode as `a3rig score` would.
  const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  const eval::ScoringProfile profile = eval::release_profile();
  eval::EpisodeReader reader(validator, profile);
  const eval::EpisodeCheck check = reader.check_text(r.episode.dump());
  std::printf("episode: %s\n", r.episode_path.c_str());
  if (o.write_lcm_log) std::printf("lcm log: %s\n", (o.out_dir / "episode.lcmlog").c_str());
  if (o.write_plot) {
    if (r.plot_problem.empty()) {
      std::printf("plot:    %s\n", (o.out_dir / "trajectory.png").c_str());
    } else {
      std::printf("plot:    not written (%s)\n", r.plot_problem.c_str());
    }
  }
  std::printf("status:  %s; mission %.1f s in %.1f s wall (%s)\n", r.status.c_str(), r.mission_time_s, r.wall_time_s,
              o.runtime == Runtime::kVirtual
                  ? (std::to_string(static_cast<int>(r.mission_time_s / std::max(r.wall_time_s, 1e-9))) + "x faster than real time").c_str()
                  : ("achieved real-time factor " + std::to_string(r.achieved_real_time_factor)).c_str());
  if (r.episode.contains("_rig") && r.episode["_rig"].contains("realtime")) {
    std::printf("real time: %s\n", realtime_summary(r.episode["_rig"]["realtime"]).c_str());
  }
  std::printf("success: %s\n", r.episode.value("success", false) ? "true" : "false");
  if (check.status == eval::EpisodeStatus::kValid) {
    const eval::Pillars p = eval::score_pillars(check.facts, profile, profile.optimal_turns);
    std::printf("α³ = %.4f  (TO %.3f  SP %.3f  TC %.3f  IQ %.3f  NR %.3f  CC %.3f)\n", p.alpha3, p.to, p.sp, p.tc,
                p.iq, p.nr, p.cc);
  } else {
    std::printf("the episode is not a valid α³-Bench episode (α³ = 0):\n");
    for (const auto& v : check.violations) std::printf("  %s\n", eval::to_string(v).c_str());
  }
  return run_exit_status(r.status);
}

}  // namespace

A3_REGISTER_COMMAND("10-run", [](CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
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
      "episode written).\n"
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
  cmd->add_option("--scenario", o.scenario,
                  "built-in scenario (survey-field, parcel-delivery, bridge-inspection, thermal-search, nfz-detour, "
                  "traffic-conflict), a scenario JSON file, or alphabench:<path> (an initial_state of the public "
                  "corpus, relative to ../shared/alphabench/eval_runs)");
  cmd->add_option("--agent", o.agent,
                  "scripted (default), llm (an OpenAI-compatible model: --llm-base-url, --llm-model), "
                  "replay:<episode.json> or replay:alphabench:<path>");
  cmd->add_option("--llm-base-url", o.llm_base_url,
                  "--agent llm: the endpoint, e.g. https://api.openai.com/v1, https://openrouter.ai/api/v1, "
                  "http://127.0.0.1:8088/v1 (default $A3_LLM_BASE_URL)");
  cmd->add_option("--llm-model", o.llm_model,
                  "--agent llm: the model, e.g. gpt-4.1-mini, anthropic/claude-haiku-4.5 (default $A3_LLM_MODEL)");
  cmd->add_option("--llm-max-tokens", o.llm_max_tokens, "--agent llm: completion tokens per call (default 2048)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--llm-timeout", o.llm_timeout_s,
                  "--agent llm: seconds one HTTP attempt may take (default 180); in real time the world flies on "
                  "meanwhile")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--llm-tools", o.llm_tools,
                  "--agent llm: native (default: every MCP tool and A2A task is an OpenAI function, the model's "
                  "tool_calls are the turn's actions and its report_turn call the turn's intent and text; without "
                  "report_turn the intent is the first call's function name and the text the message's content) or "
                  "json (the α³-Bench paper's protocol: a JSON object {intent, text, actions} in the reply's text)")
      ->check(CLI::IsMember({"native", "json"}));
  cmd->add_option("--llm-retries", o.llm_retries,
                  "--agent llm: HTTP retries of one call on 429/5xx and network errors, with backoff (default 4); "
                  "each of a turn's up to 3 attempts makes them")
      ->check(CLI::Range(0, 100));
  cmd->add_flag("--llm-stream", o.llm_stream,
                "--agent llm: stream the answers (stream: true, server-sent events); each attempt's time to the first "
                "and to the last token goes into the turn's _rig.attempt_log (ttft_s, ttlt_s)");
  cmd->add_option("--think-time", o.think_time,
                  "latency added to every agent turn: seconds, fixed:S, uniform:A,B, normal:M,SD, lognormal:MEDIAN,SIGMA, "
                  "exp:MEAN, or model:<name> (a model of the paper)");
  cmd->add_option("--runtime", args->runtime, "real (default: the wall clock) or virtual (as fast as possible)")
      ->check(CLI::IsMember({"real", "virtual"}));
  cmd->add_option("--slice", o.slice, "start on this 6G slice instead of the scenario's (eMBB, URLLC or mMTC)")
      ->check(CLI::IsMember({"eMBB", "URLLC", "mMTC"}));
  cmd->add_option("--seed", o.seed, "seed of every random stream (default 42)");
  cmd->add_option("--out", args->out, "output folder (default out/run)");
  cmd->add_option("--rtf", o.real_time_factor, "real time: simulated seconds per wall second (default 1)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--sync", o.sync,
                  "real time: lockstep (default: dynamics, bridge and flight controller advance together, paced by "
                  "the wall clock at --rtf) or free (every node on the wall clock; for a real flight controller)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, Sync>{{"lockstep", Sync::kLockstep}, {"free", Sync::kFree}}));
  cmd->add_option("--lcm-url", o.lcm_url,
                  "real time: LCM URL (default $LCM_DEFAULT_URL, else a port of its own on udpm://239.255.76.67, "
                  "ttl=0, printed at the start: give it to lcm-spy)");
  cmd->add_option("--can", o.can,
                  "real time: the CAN bus between bridge and flight controller: userspace (a private bus, default), "
                  "or an interface such as vcan0 or can0 (SocketCAN)");
  cmd->add_flag("--processes", o.processes,
                "real time: run dynamics, bridge, fc, linkemu and the vehicle side as processes of their own "
                "(`a3rig node part NAME`), talking only LCM and CAN; a process that dies ends the run (status 4)");
  cmd->add_option("--integrator", o.integrator, "cvode (default) or ode")->check(CLI::IsMember({"cvode", "ode"}));
  cmd->add_option("--max-turns", o.max_turns, "turn budget (default 12)")->check(CLI::Range(2, 100));
  cmd->add_option("--min-turns", o.min_turns, "fewest turns before the dialogue may end (default 8)")->check(CLI::Range(2, 100));
  cmd->add_flag("--no-lcm-log", [args](int64_t) { args->options.write_lcm_log = false; }, "do not write the LCM log");
  cmd->add_flag("--no-plot", [args](int64_t) { args->options.write_plot = false; }, "do not draw the trajectory");
  cmd->add_flag("-q,--quiet", o.quiet, "no progress lines");
  cmd->callback([args] { command_exit_status() = run(*args); });
});

}  // namespace a3::rigs
