// Running an episode on either runtime.
#include "rigs/run/rig_runner.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <memory>
#include <thread>

#include "bridge/can/can_bus_factory.hpp"
#include "bridge/can/userspace_bus_folder.hpp"
#include "bridge/can/virtual_can_bus.hpp"
#include "common/poll_thread.hpp"
#include "common/runtime.hpp"
#include "linkemu/link_emulator_node.hpp"
#include "rigs/outputs/episode_writer.hpp"
#include "rigs/outputs/run_outputs.hpp"
#include "rigs/run/agent_outcome.hpp"
#include "rigs/run/episode_recorder.hpp"
#include "rigs/run/lcm_log_node.hpp"
#include "rigs/run/node_configs.hpp"
#include "rigs/run/realtime_report.hpp"
#include "rigs/run/rig_nodes.hpp"
#include "rigs/run/rig_processes.hpp"
#include "rigs/run/rig_threads.hpp"
#include "vehicle/airspace_monitor_node.hpp"
#include "vehicle/tool_server_node.hpp"

namespace a3::rigs {
namespace {

// The final status: what ended the run, unless the user, a node or the endpoint ended it, or
// the agent never acted (agent_failed: the agent, not the host, is at fault), or the real-time
// contract broke (then the run, not the agent, is at fault), or the vehicle never left the
// ground on a mission that needs flight (never_flew). Virtual time has no contract (realtime null).
std::string final_status(const std::string& ended, const nlohmann::json& realtime, const RecordedEpisode& r,
                         const Scenario& s) {
  if (ended == "interrupted" || ended.rfind("node_failed", 0) == 0 || ended.rfind("endpoint_failed", 0) == 0) {
    return ended;
  }
  if (std::string why = agent_failure_status(r.turns); !why.empty()) return why;
  if (const std::string why = realtime_violations(realtime); !why.empty()) return "realtime_violated: " + why;
  const std::string grounded = never_flew_status(r.has_flown, r.max_altitude_m, s.mission.objectives.size());
  return grounded.empty() ? ended : grounded;
}

using SteadyClock = std::chrono::steady_clock;

constexpr double kPostDialogueWait_s = 240.0;  // after the last turn, time left to land
constexpr double kAfterCrash_s = 2.0;

// Why the episode should end now, or "".
std::string end_reason(const RecordedEpisode& r, bool dialogue_done, double mission_s, double dialogue_end_s,
                       double crash_s, double time_limit_s) {
  if (crash_s >= 0.0 && mission_s - crash_s >= kAfterCrash_s) return "crashed";
  if (std::string why = endpoint_failure_status(r.turns); !why.empty()) return why;
  if (dialogue_done) {
    const bool landed = r.last_state.on_ground && !r.last_fc.armed;
    if (landed) return "completed";
    if (dialogue_end_s >= 0.0 && mission_s - dialogue_end_s >= kPostDialogueWait_s) return "dialogue_ended_airborne";
  }
  if (mission_s >= time_limit_s) return "time_limit";
  return "";
}

std::string describe_turn(const nlohmann::json& t, const RecordedEpisode& r) {
  std::string names;
  for (const auto& a : t.value("actions", nlohmann::json::array())) {
    names += (names.empty() ? "" : ", ") + (a.value("type", "") == "a2a" ? "a2a:" + a.value("task", "") : a.value("name", ""));
  }
  std::string outcomes;
  for (const auto& o : t.value("obs", nlohmann::json::array())) {
    std::string status = o.is_object() ? o.value("status", "") : "";
    if (status.empty() && o.is_object() && o.contains("result") && o["result"].is_object()) status = o["result"].value("status", "ok");
    outcomes += (outcomes.empty() ? "" : ",") + (status.empty() ? std::string("ok") : status);
  }
  char text[600];
  const auto& rig = t.value("_rig", nlohmann::json::object());
  std::snprintf(text, sizeof text, "turn %2d %-5s %-24s [%s] -> [%s]  t=%.1f s  z=%.1f m  battery %.0f %%  %s",
                t.value("turn", 0), t.value("speaker", "").c_str(), t.value("intent", "").c_str(), names.c_str(),
                outcomes.c_str(), rig.value("finished_s", 0.0), r.last_state.p_W_m[2], r.last_state.battery_pct,
                t.value("net", nlohmann::json::object()).value("slice", "").c_str());
  return text;
}

// Progress lines for what is new since the last call.
struct Reporter {
  const ProgressFn& progress;
  std::size_t turns = 0, safety = 0;
  void operator()(const RecordedEpisode& r) {
    if (!progress) return;
    for (; turns < r.turns.size(); ++turns) progress(describe_turn(r.turns[turns], r));
    for (; safety < r.safety.size(); ++safety) {
      const auto& e = r.safety[safety];
      char text[300];
      std::snprintf(text, sizeof text, "safety: %s (%s) at t=%.1f s, value %.2f: %s", e.kind.c_str(), e.source.c_str(),
                    e.utime_us * 1e-6, e.value, e.detail.c_str());
      progress(text);
    }
  }
};

struct RunEnd {
  std::string status;
  double mission_s = 0.0;
  double wall_s = 0.0;
  nlohmann::json counters;   // {node: counters}
  nlohmann::json realtime;   // real time only
};

RunResult finish(const Scenario& s, const RunOptions& o, RigNodes& n, const RunEnd& end, int64_t start_unix_us,
                 const ProgressFn& progress) {
  RunResult result;
  result.status = end.status;
  result.mission_time_s = end.mission_s;
  result.wall_time_s = end.wall_s;
  result.achieved_real_time_factor = end.wall_s > 0.0 ? end.mission_s / end.wall_s : 0.0;
  const RecordedEpisode rec = n.recorder->snapshot();
  RunFacts facts;
  facts.status = end.status;
  facts.agent_name = n.conversation ? "a3rig/" + o.agent : o.agent;
  facts.mission_time_s = end.mission_s;
  facts.wall_time_s = end.wall_s;
  facts.achieved_real_time_factor = o.runtime == Runtime::kReal ? result.achieved_real_time_factor : 0.0;
  facts.start_unix_us = start_unix_us;
  facts.counters = end.counters;
  facts.realtime = end.realtime;
  if (n.log) n.log->close();
  WrittenOutputs written = write_run_outputs(s, o, rec, facts, n.log ? n.log->failure() : "");
  result.flight_status = end.status;
  result.status = written.status;
  result.episode = std::move(written.episode);
  result.episode_path = written.episode_path;
  result.plot_problem = written.plot_problem;
  result.report_problem = written.report_problem;
  result.outputs_lost = written.lost;
  if (progress) {
    char text[200];
    std::snprintf(text, sizeof text, "episode ended: %s after %.1f s of mission (%.1f s wall)", end.status.c_str(),
                  end.mission_s, end.wall_s);
    progress(text);
    for (const std::string& what : result.outputs_lost) progress("output lost: " + what);
  }
  return result;
}

// A run's own LCM port on the usual multicast group (the loopback route covers the group, any
// port), so that two runs on one host never hear each other; an explicit URL or
// $LCM_DEFAULT_URL wins. An even port: the next one carries the lockstep answers.
std::string private_lcm_url(const std::string& requested) {
  if (!requested.empty()) return requested;
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env != nullptr && *env != '\0') return env;
  return "udpm://239.255.76.67:" + std::to_string(7668 + 2 * (::getpid() % 10000)) + "?ttl=0";
}

int64_t unix_now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Ctrl-C while the agent decides (real time): the decision is stopped and its turn, recorded
// as interrupted, gets up to 2 s of wall time to reach the recorder.
void record_interrupted_turn(RigNodes& n) {
  if (!n.conversation || !n.conversation->interrupt()) return;
  const auto deadline = SteadyClock::now() + std::chrono::seconds(2);
  while (SteadyClock::now() < deadline) {
    if (n.conversation->finished() && n.recorder->snapshot().turns.size() >= n.conversation->turns().size()) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// Virtual time runs the agent in place, on this thread: a watcher stops its decision on Ctrl-C
// so that the loop below gets to see the stop.
std::unique_ptr<common::PollThread> watch_for_interrupt(const std::atomic<bool>* stop, RigNodes& n) {
  if (stop == nullptr || !n.conversation) return nullptr;
  return std::make_unique<common::PollThread>(std::chrono::milliseconds(20), [stop, &n] {
    if (!stop->load()) return false;
    n.conversation->interrupt();
    return true;
  });
}

RunResult run_virtual(const Scenario& s, const RunOptions& o, const RigConfigs& cfg, const ProgressFn& progress,
                      const std::atomic<bool>* stop) {
  const auto wall0 = SteadyClock::now();
  const int64_t unix0 = unix_now_us();
  common::VirtualRuntime rt;
  bridge::VirtualCanBus can(rt.scheduler());
  auto can_bridge = can.attach("bridge");
  auto can_fc = can.attach("fc");
  RigNodes n = make_rig_nodes(all_rig_parts(), cfg, o, s, {{can_bridge.get(), can_fc.get()}}, false);
  for (common::Node* node : n.in_start_order()) rt.add(*node);
  Reporter report{progress};
  std::string status;
  double t = 0.0, dialogue_end_s = -1.0, crash_s = -1.0;
  const auto interrupt_watcher = watch_for_interrupt(stop, n);
  try {
    while (status.empty()) {
      t += 0.5;
      rt.run_until(static_cast<int64_t>(t * 1e6));
      const bool done = n.conversation->finished();
      if (done && dialogue_end_s < 0.0) dialogue_end_s = t;
      // Read in place: a copy of the episode so far every half second grows with the mission.
      n.recorder->inspect([&](const RecordedEpisode& r) {
        report(r);
        if (r.last_state.crashed && crash_s < 0.0) crash_s = t;
        status = end_reason(r, done, t, dialogue_end_s, crash_s, s.mission.time_limit_s);
      });
      // A stop (Ctrl-C, an MCP client gone) wins over what it caused: a dialogue it cut short
      // must not read as the mission's end.
      if (stop != nullptr && stop->load()) status = "interrupted";
    }
  } catch (const std::exception& e) {
    status = std::string("node_failed: ") + e.what();
  }
  status = final_status(status, nullptr, n.recorder->snapshot(), s);
  RunEnd end{status, t, std::chrono::duration<double>(SteadyClock::now() - wall0).count(), n.counters(), nullptr};
  return finish(s, o, n, end, unix0, progress);
}

// A node whose statistics (published every second of wall time) stop coming for this long is
// frozen or gone: three missed reports. A process that dies is noticed within 50 ms instead.
constexpr double kNodeSilence_s = 3.0;

std::string silent_node(const RecordedEpisode& r) {
  const double now_us = static_cast<double>(common::WallClock::monotonic_now_ns()) * 1e-3;
  for (const auto& [name, n] : r.nodes) {
    if (!n.final && now_us - static_cast<double>(n.wall_utime_us) > kNodeSilence_s * 1e6) {
      return name + " (pid " + std::to_string(n.pid) + ") is unresponsive: no statistics for " +
             std::to_string(static_cast<int>(kNodeSilence_s)) + " s of wall time";
    }
  }
  return "";
}

// Waits (a little) until every node that reported has sent its final statistics.
void await_final_stats(const EpisodeRecorderNode& recorder, double timeout_s) {
  const auto deadline = SteadyClock::now() + std::chrono::duration<double>(timeout_s);
  while (SteadyClock::now() < deadline) {
    bool all_final = true;
    for (const auto& [name, n] : recorder.snapshot().nodes) all_final &= n.final || name == recorder.name();
    if (all_final) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

std::string status_line(double mission_s, double wall_s, const RecordedEpisode& r) {
  char text[300];
  std::snprintf(text, sizeof text, "t=%.0f s  z=%.1f m  battery %.0f %%  slice %s  real-time factor %.3f", mission_s,
                r.last_state.p_W_m[2], r.last_state.battery_pct, r.last_slice.c_str(), mission_s / wall_s);
  std::string line = text;
  if (auto it = r.nodes.find("dynamics"); it != r.nodes.end() && it->second.stats.contains("timing")) {
    const auto& t = it->second.stats["timing"];
    if (t.contains("lockstep_waits")) {
      std::snprintf(text, sizeof text, "  lockstep waits %.0f (%.2f s)", t.value("lockstep_waits", 0.0),
                    t.value("lockstep_wait_total_s", 0.0));
      line += text;
    }
  }
  return line;
}


RunResult run_real(const Scenario& s, const RunOptions& o, const RigConfigs& cfg, const ProgressFn& progress,
                   const std::atomic<bool>* stop) {
  const auto wall0 = SteadyClock::now();
  const int64_t unix0 = unix_now_us();
  const std::string can_spec = o.can == "userspace" ? "userspace:a3rig-run-" + std::to_string(::getpid()) : o.can;
  // The bus's folder goes at every way out of this function, also after a child's crash.
  const bridge::UserspaceBusFolderGuard can_folder(can_spec);
  const std::string lcm_url = private_lcm_url(o.lcm_url);
  {
    common::LcmBus probe(lcm_url);
    probe.check_loopback();
  }
  const bool agent_in_thread = o.agent == "llm" || o.agent == "mcp";  // decide() blocks on a wall clock
  std::unique_ptr<bridge::CanBus> can_bridge, can_fc;
  std::unique_ptr<RigProcesses> children;
  std::vector<RigPart> in_process = all_rig_parts();
  // Declared before the nodes: a node's destructor cancels its timers on its thread's executor.
  std::unique_ptr<RigThreads> threads;
  if (o.processes) {
    in_process = {RigPart::kGround};
    children = std::make_unique<RigProcesses>(o.a3rig_exe, rig_parts_outside_ground(), o, lcm_url, can_spec);
    if (progress) progress("started dynamics, bridge, fc, linkemu and vehicle as processes; waiting for them");
    if (const std::string why = children->wait_ready(60.0); !why.empty()) {
      children->stop();
      throw std::runtime_error("a3rig run --processes: " + why);
    }
  } else {
    can_bridge = bridge::open_can_bus(can_spec);
    can_fc = bridge::open_can_bus(can_spec);
  }
  RigNodes n = make_rig_nodes(in_process, cfg, o, s, {{can_bridge.get(), can_fc.get()}}, agent_in_thread);
  if (progress) {
    progress("LCM: " + lcm_url + "  CAN: " + (can_bridge ? can_bridge->name() : can_spec) + "  sync: " +
             to_string(o.sync) + (o.sync == Sync::kLockstep ? " (the vehicle waits for its flight controller)" : ""));
  }
  const int64_t epoch_ns = common::WallClock::monotonic_now_ns();
  threads = std::make_unique<RigThreads>(n, cfg, o, lcm_url, epoch_ns);
  if (children) children->go(epoch_ns);
  threads->start();
  Reporter report{progress};
  WindowMeter windows;
  std::string status;
  double dialogue_end_s = -1.0, crash_s = -1.0, mission_s = 0.0;
  auto last_line = SteadyClock::now();
  while (status.empty()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    mission_s = threads->clock().now_s();
    const double wall_s = std::chrono::duration<double>(SteadyClock::now() - wall0).count();
    windows.sample(wall_s, mission_s);
    const RecordedEpisode r = n.recorder->snapshot();
    report(r);
    if (const std::string why = threads->failure(); !why.empty()) status = "node_failed: " + why;
    if (status.empty() && children) {
      if (const std::string why = children->check(); !why.empty()) status = "node_failed: " + why;
    }
    if (status.empty()) {
      if (const std::string why = silent_node(r); !why.empty()) status = "node_failed: " + why;
    }
    const bool done = n.conversation->finished();
    if (done && dialogue_end_s < 0.0) dialogue_end_s = mission_s;
    if (r.last_state.crashed && crash_s < 0.0) crash_s = mission_s;
    if (status.empty() && stop != nullptr && stop->load()) status = "interrupted";  // before what the stop caused
    if (status.empty()) status = end_reason(r, done, mission_s, dialogue_end_s, crash_s, s.mission.time_limit_s);
    if (progress && SteadyClock::now() - last_line > std::chrono::seconds(10)) {
      last_line = SteadyClock::now();
      progress(status_line(mission_s, wall_s, r));
    }
  }
  if (status == "interrupted") record_interrupted_turn(n);
  const double wall_s = std::chrono::duration<double>(SteadyClock::now() - wall0).count();
  if (children) children->stop();
  threads->stop_all_but_first();
  await_final_stats(*n.recorder, 1.0);
  threads->stop_all();
  const RecordedEpisode r = n.recorder->snapshot();
  RunEnd end;
  end.mission_s = mission_s;
  end.wall_s = wall_s;
  end.counters = counters_from_stats(r.nodes);
  end.realtime = realtime_report(o, {mission_s, wall_s, windows.worst()}, r.nodes);
  end.status = final_status(status, end.realtime, r, s);
  return finish(s, o, n, end, unix0, progress);
}

}  // namespace

int run_exit_status(const std::string& status) {
  if (status == "interrupted") return 3;
  if (status.rfind("node_failed", 0) == 0) return 4;
  if (status.rfind("realtime_violated", 0) == 0) return 5;
  if (status.rfind("agent_failed", 0) == 0) return 6;
  if (status.rfind("endpoint_failed", 0) == 0) return 7;
  if (status.rfind("output_failed", 0) == 0) return 8;
  if (status.rfind("never_flew", 0) == 0) return 9;
  return 0;
}

RunResult run_episode(const Scenario& s, const RunOptions& o, const ProgressFn& progress, const std::atomic<bool>* stop) {
  check_output_space(s, o);  // nothing flies when the outputs cannot fit
  const RigConfigs cfg = make_rig_configs(s, o);
  return o.runtime == Runtime::kVirtual ? run_virtual(s, o, cfg, progress, stop) : run_real(s, o, cfg, progress, stop);
}

}  // namespace a3::rigs
