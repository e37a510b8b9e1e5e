// The shared options of `a3rig run` and `a3rig mcp`.
#include "rigs/cli/scenario_run_flags.hpp"

#include <cstdlib>
#include <map>
#include <stdexcept>

#include "common/log.hpp"
#include "rigs/cli/run_flag_options.hpp"

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
  add_run_flags(cmd, f.options,
                {RunFlag::kScenario, RunFlag::kThinkTime, RunFlag::kRuntime, RunFlag::kSlice, RunFlag::kSeed,
                 RunFlag::kOut, RunFlag::kRtf, RunFlag::kSync, RunFlag::kLcmUrl, RunFlag::kCan, RunFlag::kIntegrator,
                 RunFlag::kMaxTurns, RunFlag::kMinTurns, RunFlag::kNoLcmLog, RunFlag::kNoPlot, RunFlag::kNoReport,
                 RunFlag::kQuiet});
}

}  // namespace a3::rigs
