// The run flags' options.
#include "rigs/cli/run_flag_options.hpp"

#include <map>
#include <string>

#include "agent/conversation/think_time.hpp"
#include "dynamics/integrator_kind.hpp"
#include "linkemu/network_state.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/scenario/scenario.hpp"
#include "rigs/scenario/shared_dir.hpp"

namespace a3::rigs {
namespace {

std::string joined(const std::vector<std::string>& names, const std::string& last_word) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    out += i == 0 ? "" : i + 1 == names.size() ? " " + last_word + " " : ", ";
    out += names[i];
  }
  return out;
}

std::string piped(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : "|") + n;
  return out;
}

std::string scenario_help() {
  return "built-in scenario (" + joined(builtin_scenario_names(), "or") +
         "), a generated mission gen:SEED[:easy|medium|hard|knob=value+...] (e.g. gen:7:hard; `a3rig scenario "
         "generate --help` lists the knobs), a scenario JSON file, or alphabench:<path> (an initial_state of the "
         "public corpus, relative to ../shared/alphabench/eval_runs)";
}

std::string think_time_help() {
  std::vector<std::string> models;
  for (const auto& profile : agent::model_latency_profiles()) models.push_back(profile.name);
  return "latency added to every agent turn: seconds, fixed:S, uniform:A,B, normal:M,SD, lognormal:MEDIAN,SIGMA, "
         "exp:MEAN, or model:<name>, a model of the paper (" + joined(models, "or") + ")";
}

CLI::Option* add_switch(CLI::App& cmd, RunFlag flag, bool& field, bool value_when_given, const std::string& help) {
  return cmd.add_flag(flag_name(flag), [&field, value_when_given](int64_t) { field = value_when_given; }, help);
}

}  // namespace

CLI::Option* add_run_flag(CLI::App& cmd, RunOptions& o, RunFlag flag) {
  const std::string name = flag_name(flag);
  switch (flag) {
    case RunFlag::kScenario: return cmd.add_option(name, o.scenario, scenario_help());
    case RunFlag::kAgent:
      return cmd.add_option(name, o.agent,
                            "scripted (default), llm (an OpenAI-compatible model: --llm-base-url, --llm-model), "
                            "replay:<episode.json> or replay:alphabench:<path>");
    case RunFlag::kThinkTime: return cmd.add_option(name, o.think_time, think_time_help());
    case RunFlag::kRuntime:
      return cmd.add_option(name, o.runtime, "real (default: the wall clock) or virtual (as fast as possible)")
          ->transform(CLI::CheckedTransformer(std::map<std::string, Runtime>{{"real", Runtime::kReal},
                                                                             {"virtual", Runtime::kVirtual}}))
          ->option_text("real|virtual");
    case RunFlag::kSlice:
      return cmd
          .add_option_function<std::string>(
              name, [&o](const std::string& slice) { o.slice = linkemu::parse_slice(slice); },
              "start on this 6G slice instead of the scenario's (" + joined(linkemu::slice_names(), "or") + ")")
          ->check(CLI::IsMember(linkemu::slice_names()))
          ->option_text(piped(linkemu::slice_names()));
    case RunFlag::kSeed: return cmd.add_option(name, o.seed, "seed of every random stream (default 42)");
    case RunFlag::kOut:
      return cmd.add_option(name, o.out_dir, "output folder, created when absent (default out/run)")
          ->check(output_folder());
    case RunFlag::kRtf:
      return cmd.add_option(name, o.real_time_factor, "real time: simulated seconds per wall second (default 1)")
          ->check(positive());
    case RunFlag::kSync:
      return cmd.add_option(name, o.sync,
                            "real time: lockstep (default: dynamics, bridge and flight controller advance together, "
                            "paced by the wall clock at --rtf) or free (every node on the wall clock; for a real "
                            "flight controller)")
          ->transform(CLI::CheckedTransformer(sync_by_name()))
          ->option_text("lockstep|free");
    case RunFlag::kLcmUrl:
      return cmd.add_option(name, o.lcm_url,
                            "real time: LCM URL (default $LCM_DEFAULT_URL, else a port of its own on "
                            "udpm://239.255.76.67, ttl=0, printed at the start: give it to lcm-spy; lockstep also "
                            "uses the next port, for the ground nodes' answers to the time master)");
    case RunFlag::kCan:
      return cmd.add_option(name, o.can,
                            "real time: the CAN bus between bridge and flight controller: userspace (a private bus, "
                            "default), or an interface such as vcan0 or can0 (SocketCAN)");
    case RunFlag::kIntegrator:
      return cmd.add_option(name, o.integrator,
                            "rk4 (default: fixed-step Runge-Kutta), cvode (adaptive, the accuracy reference) or ode")
          ->transform(CLI::CheckedTransformer(dynamics::integrator_by_name()))
          ->option_text(piped(dynamics::integrator_names()));
    case RunFlag::kDynamicsRate:
      return cmd.add_option(name, o.dynamics_rate_hz, "dynamics step rate (default 250)")->check(positive());
    case RunFlag::kSharedDir:
      o.shared_dir = default_shared_dir();
      return cmd.add_option(name, o.shared_dir,
                            "the ../shared folder (alphabench scenarios, traces; default $A3_SHARED_DIR, else "
                            "../shared here or beside the repository)");
    case RunFlag::kMaxTurns:
      return cmd.add_option(name, o.max_turns, "turn budget (default 12)")->check(between(2, 100));
    case RunFlag::kMinTurns:
      return cmd.add_option(name, o.min_turns, "fewest turns before the dialogue may end (default 8)")
          ->check(between(2, 100));
    case RunFlag::kNoLcmLog: return add_switch(cmd, flag, o.write_lcm_log, false, "do not write the LCM log");
    case RunFlag::kNoPlot: return add_switch(cmd, flag, o.write_plot, false, "do not draw the trajectory");
    case RunFlag::kNoReport:
      return add_switch(cmd, flag, o.write_report, false,
                        "do not write report.html (the episode's map, timelines, score and dialogue in one page)");
    case RunFlag::kQuiet:
      return cmd.add_flag("-q," + name, o.quiet, "no progress lines and no [info] log lines (warnings and errors stay)");
  }
  return nullptr;
}

void add_run_flags(CLI::App& cmd, RunOptions& o, std::initializer_list<RunFlag> flags) {
  for (RunFlag flag : flags) add_run_flag(cmd, o, flag);
}

}  // namespace a3::rigs
