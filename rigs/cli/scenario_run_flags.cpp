// The shared options of `a3rig run` and `a3rig mcp`.
#include "rigs/cli/scenario_run_flags.hpp"

#include <cstdlib>
#include <map>
#include <stdexcept>

#include "agent/conversation/think_time.hpp"
#include "common/log.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/core/scenario.hpp"

namespace a3::rigs {

namespace {

// The rig's nodes each open an LCM instance of their own; memq:// delivers only inside one, so
// they would never hear each other and simulated time would never pass.
void refuse_in_process_lcm(const std::string& requested_url) {
  const char* env = std::getenv("LCM_DEFAULT_URL");
  const std::string url = !requested_url.empty() ? requested_url : env != nullptr ? env : "";
  if (url.rfind("memq://", 0) != 0) return;
  throw std::invalid_argument(std::string(requested_url.empty() ? "LCM_DEFAULT_URL" : "--lcm-url") + " '" + url +
                              "': memq:// delivers only inside one LCM instance and each rig node opens its own, so "
                              "the run would stay at t = 0 s; use udpm:// (the default; as root scripts/lcm-loopback.sh "
                              "routes it over loopback) or --runtime virtual");
}

}  // namespace

void ScenarioRunFlags::apply() {
  options.runtime = runtime == "virtual" ? Runtime::kVirtual : Runtime::kReal;
  if (!out.empty()) options.out_dir = out;
  if (options.processes && options.runtime == Runtime::kVirtual) {
    throw std::invalid_argument("--processes: runs in real time only (virtual time is one process by design); drop "
                                "--runtime virtual or --processes");
  }
  if (options.runtime == Runtime::kReal) refuse_in_process_lcm(options.lcm_url);
  // -q: no progress lines and no [info] log lines either (warnings and errors stay), unless
  // A3_LOG_LEVEL says otherwise.
  const char* level = std::getenv("A3_LOG_LEVEL");
  if (options.quiet && (level == nullptr || *level == '\0')) common::set_log_level(common::LogLevel::kWarn);
}

void add_scenario_run_flags(CLI::App& cmd, ScenarioRunFlags& f) {
  RunOptions& o = f.options;
  std::string builtins;
  for (const auto& name : builtin_scenario_names()) builtins += (builtins.empty() ? "" : ", ") + name;
  cmd.add_option("--scenario", o.scenario,
                 "built-in scenario (" + builtins + "), a generated mission gen:SEED[:easy|medium|hard|knob=value+...] "
                 "(e.g. gen:7:hard; `a3rig scenario generate --help` lists the knobs), a scenario JSON file, or alphabench:<path> (an initial_state of "
                 "the public corpus, relative to ../shared/alphabench/eval_runs)");
  std::string models;
  for (const auto& profile : agent::model_latency_profiles()) models += (models.empty() ? "" : ", ") + profile.name;
  cmd.add_option("--think-time", o.think_time,
                 "latency added to every agent turn: seconds, fixed:S, uniform:A,B, normal:M,SD, lognormal:MEDIAN,SIGMA, "
                 "exp:MEAN, or model:<name>, a model of the paper (" + models + ")");
  cmd.add_option("--runtime", f.runtime, "real (default: the wall clock) or virtual (as fast as possible)")
      ->check(CLI::IsMember({"real", "virtual"}));
  cmd.add_option("--slice", o.slice, "start on this 6G slice instead of the scenario's (eMBB, URLLC or mMTC)")
      ->check(CLI::IsMember({"eMBB", "URLLC", "mMTC"}));
  cmd.add_option("--seed", o.seed, "seed of every random stream (default 42)");
  cmd.add_option("--out", f.out, "output folder, created when absent (default out/run)")->check(output_folder());
  cmd.add_option("--rtf", o.real_time_factor, "real time: simulated seconds per wall second (default 1)")
      ->check(a3::rigs::positive());
  cmd.add_option("--sync", o.sync,
                 "real time: lockstep (default: dynamics, bridge and flight controller advance together, paced by "
                 "the wall clock at --rtf) or free (every node on the wall clock; for a real flight controller)")
      ->transform(CLI::CheckedTransformer(sync_by_name()))
      ->option_text("lockstep|free");
  cmd.add_option("--lcm-url", o.lcm_url,
                 "real time: LCM URL (default $LCM_DEFAULT_URL, else a port of its own on udpm://239.255.76.67, "
                 "ttl=0, printed at the start: give it to lcm-spy; lockstep also uses the next port, for the ground "
                 "nodes' answers to the time master)");
  cmd.add_option("--can", o.can,
                 "real time: the CAN bus between bridge and flight controller: userspace (a private bus, default), "
                 "or an interface such as vcan0 or can0 (SocketCAN)");
  cmd.add_option("--integrator", o.integrator, "rk4 (default: fixed-step Runge-Kutta), cvode (adaptive, the accuracy reference) or ode")->check(CLI::IsMember({"rk4", "cvode", "ode"}));
  cmd.add_option("--max-turns", o.max_turns, "turn budget (default 12)")->check(a3::rigs::between(2, 100));
  cmd.add_option("--min-turns", o.min_turns, "fewest turns before the dialogue may end (default 8)")->check(a3::rigs::between(2, 100));
  cmd.add_flag("--no-lcm-log", [&o](int64_t) { o.write_lcm_log = false; }, "do not write the LCM log");
  cmd.add_flag("--no-plot", [&o](int64_t) { o.write_plot = false; }, "do not draw the trajectory");
  cmd.add_flag("--no-report", [&o](int64_t) { o.write_report = false; },
               "do not write report.html (the episode's map, timelines, score and dialogue in one page)");
  cmd.add_flag("-q,--quiet", o.quiet, "no progress lines and no [info] log lines (warnings and errors stay)");
}

}  // namespace a3::rigs
