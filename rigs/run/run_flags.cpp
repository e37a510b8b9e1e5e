// Run options written back as flags.
#include "rigs/run/run_flags.hpp"

#include <cstdio>
#include <cstdlib>

#include "dynamics/integrator_kind.hpp"
#include "linkemu/network_state.hpp"

namespace a3::rigs {
namespace {

// The shortest text that parses back to the same double (2.5, 0.1, not 0.10000000000000001).
std::string exact(double v) {
  char text[64];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

// The value a flag writes; nullopt leaves the flag out (a switch that is off, an unset option).
std::optional<std::string> value_of(const RunOptions& o, RunFlag flag) {
  switch (flag) {
    case RunFlag::kScenario: return o.scenario;
    case RunFlag::kAgent: return o.agent;
    case RunFlag::kThinkTime: return o.think_time;
    case RunFlag::kRuntime: return std::string(o.runtime == Runtime::kVirtual ? "virtual" : "real");
    case RunFlag::kSlice: return o.slice ? std::optional<std::string>(linkemu::to_string(*o.slice)) : std::nullopt;
    case RunFlag::kSeed: return std::to_string(o.seed);
    case RunFlag::kOut: return o.out_dir.string();
    case RunFlag::kRtf: return exact(o.real_time_factor);
    case RunFlag::kSync: return std::string(to_string(o.sync));
    case RunFlag::kLcmUrl: return o.lcm_url.empty() ? std::nullopt : std::optional<std::string>(o.lcm_url);
    case RunFlag::kCan: return o.can;
    case RunFlag::kIntegrator: return std::string(dynamics::to_string(o.integrator));
    case RunFlag::kDynamicsRate: return exact(o.dynamics_rate_hz);
    case RunFlag::kSharedDir: return o.shared_dir.string();
    case RunFlag::kMaxTurns: return std::to_string(o.max_turns);
    case RunFlag::kMinTurns: return std::to_string(o.min_turns);
    case RunFlag::kNoLcmLog: return o.write_lcm_log ? std::nullopt : std::optional<std::string>("");
    case RunFlag::kNoPlot: return o.write_plot ? std::nullopt : std::optional<std::string>("");
    case RunFlag::kNoReport: return o.write_report ? std::nullopt : std::optional<std::string>("");
    case RunFlag::kQuiet: return o.quiet ? std::optional<std::string>("") : std::nullopt;
  }
  return std::nullopt;
}

bool is_switch(RunFlag flag) {
  return flag == RunFlag::kNoLcmLog || flag == RunFlag::kNoPlot || flag == RunFlag::kNoReport || flag == RunFlag::kQuiet;
}

}  // namespace

const char* flag_name(RunFlag flag) {
  switch (flag) {
    case RunFlag::kScenario: return "--scenario";
    case RunFlag::kAgent: return "--agent";
    case RunFlag::kThinkTime: return "--think-time";
    case RunFlag::kRuntime: return "--runtime";
    case RunFlag::kSlice: return "--slice";
    case RunFlag::kSeed: return "--seed";
    case RunFlag::kOut: return "--out";
    case RunFlag::kRtf: return "--rtf";
    case RunFlag::kSync: return "--sync";
    case RunFlag::kLcmUrl: return "--lcm-url";
    case RunFlag::kCan: return "--can";
    case RunFlag::kIntegrator: return "--integrator";
    case RunFlag::kDynamicsRate: return "--dynamics-rate-hz";
    case RunFlag::kSharedDir: return "--shared-dir";
    case RunFlag::kMaxTurns: return "--max-turns";
    case RunFlag::kMinTurns: return "--min-turns";
    case RunFlag::kNoLcmLog: return "--no-lcm-log";
    case RunFlag::kNoPlot: return "--no-plot";
    case RunFlag::kNoReport: return "--no-report";
    case RunFlag::kQuiet: return "--quiet";
  }
  return "?";
}

std::vector<std::string> to_argv(const RunOptions& o, std::initializer_list<RunFlag> flags) {
  std::vector<std::string> argv;
  for (RunFlag flag : flags) {
    const std::optional<std::string> value = value_of(o, flag);
    if (!value) continue;
    argv.emplace_back(flag_name(flag));
    if (!is_switch(flag)) argv.push_back(*value);
  }
  return argv;
}

}  // namespace a3::rigs
