// What `a3rig run` was asked to do, parsed once at the command line into typed fields
// (rigs/run/run_flags.hpp names the flags and writes them back).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "dynamics/integrator_kind.hpp"
#include "linkemu/network_state.hpp"

namespace a3::agent {
class Agent;
}

namespace a3::rigs {

enum class Runtime { kVirtual, kReal };
// Real time: the vehicle's nodes in lockstep with their flight controller (default), or
// free-running on the wall clock (a real flight controller on a real bus). DESIGN.md "Time".
enum class Sync { kLockstep, kFree };
const char* to_string(Sync sync);
// The --sync words: "lockstep", "free".
inline const std::map<std::string, Sync>& sync_by_name() {
  static const std::map<std::string, Sync> kNames = {{"lockstep", Sync::kLockstep}, {"free", Sync::kFree}};
  return kNames;
}

struct RunOptions {
  std::string scenario = "survey-field";  // built-in name, file, or alphabench:<path>
  std::string agent = "scripted";          // scripted | replay:<episode file> | llm | mcp
  // When set, makes the agent instead of `agent` (`a3rig mcp`: the agent is the MCP session's).
  std::function<std::unique_ptr<agent::Agent>()> agent_factory;
  // --agent llm: the OpenAI-compatible endpoint (rigs/run/llm_run.hpp). No API key here: it
  // comes only from the environment, so that it never shows in a command line or a record.
  std::string llm_base_url;                // empty: $A3_LLM_BASE_URL
  std::string llm_model;                   // empty: $A3_LLM_MODEL
  int llm_max_tokens = 2048;               // completion tokens per call
  double llm_connect_timeout_s = 10.0;
  double llm_timeout_s = 180.0;            // per HTTP attempt
  std::string llm_tools = "native";        // native (OpenAI tool calls) | json (a JSON object in the text)
  bool llm_stream = false;                 // stream the answers (server-sent events; ttft/ttlt in _rig)
  int llm_retries = 4;                     // HTTP retries of one call (429/5xx/network), with backoff
  std::string think_time = "0";            // see agent/conversation/think_time.hpp
  std::optional<linkemu::Slice> slice;     // overrides the scenario's initial slice; unset: keep
  Runtime runtime = Runtime::kReal;
  uint64_t seed = 42;
  std::filesystem::path out_dir = "out/run";
  double real_time_factor = 1.0;
  Sync sync = Sync::kLockstep;
  std::string lcm_url;                     // real time: default udpm ttl=0
  std::string can = "userspace";           // real time: userspace (private bus) or an interface (vcan0, can0)
  bool processes = false;                  // real time: every part but the ground side as a process of its own
  std::filesystem::path a3rig_exe = "/proc/self/exe";  // what --processes starts (`a3rig node part ...`)
  dynamics::IntegratorKind integrator = dynamics::IntegratorKind::kRk4;
  double dynamics_rate_hz = 250.0;
  int min_turns = 8;
  int max_turns = 12;
  bool write_lcm_log = true;
  bool write_plot = true;
  bool write_report = true;  // report.html beside episode.json (episode_report.hpp)
  bool quiet = false;
  std::filesystem::path shared_dir = "../shared";
};

}  // namespace a3::rigs
