// Running an episode on either runtime.
#include "rigs/core/rig_runner.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <memory>
#include <thread>

#include "agent/vehicle/airspace_monitor_node.hpp"
#include "agent/vehicle/tool_server_node.hpp"
#include "bridge/can/can_bus_factory.hpp"
#include "bridge/can/virtual_can_bus.hpp"
#include "common/runtime.hpp"
#include "linkemu/link_emulator_node.hpp"
#include "rigs/core/episode_recorder.hpp"
#include "rigs/core/episode_writer.hpp"
#include "rigs/core/lcm_log_node.hpp"
#include "rigs/core/node_configs.hpp"
#include "rigs/core/rig_nodes.hpp"
#include "rigs/core/rig_processes.hpp"

namespace a3::rigs {
namespace {

using SteadyClock = std::chrono::steady_clock;

constexpr double kPostDialogueWait_s = 240.0;  // after the last turn, time left to land
constexpr double kAfterCrash_s = 2.0;

// Why the episode should end now, or "".
std::string end_reason(const RecordedEpisode& r, bool dialogue_done, double mission_s, double dialogue_end_s,
                       double crash_s, double time_limit_s) {
  if (crash_s >= 0.0 && mission_s - crash_s >= kAfterCrash_s) return "crashed";
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

RunResult finish(const Scenario& s, const RunOptions& o, RigNodes& n, const std::string& status, double mission_s,
                 double wall_s, int64_t start_unix_us, const ProgressFn& progress) {
  RunResult result;
  result.status = status;
  result.mission_time_s = mission_s;
  result.wall_time_s = wall_s;
  result.achieved_real_time_factor = wall_s > 0.0 ? mission_s / wall_s : 0.0;
  const RecordedEpisode rec = n.recorder->snapshot();
  RunFacts facts;
  facts.status = status;
  facts.agent_name = n.conversation ? "a3rig/" + o.agent : o.agent;
  facts.mission_time_s = mission_s;
  facts.wall_time_s = wall_s;
  facts.achieved_real_time_factor = o.runtime == Runtime::kReal ? result.achieved_real_time_factor : 0.0;
  facts.start_unix_us = start_unix_us;
  facts.counters = n.counters();
  if (n.log) n.log->close();
  result.episode = build_episode(s, o, rec, facts);
  write_episode(o.out_dir, result.episode);
  result.episode_path = o.out_dir / "episode.json";
  if (o.write_plot) result.plot_problem = write_trajectory_plot(o.out_dir, s, rec);
  if (progress) {
    char text[200];
    std::snprintf(text, sizeof text, "episode ended: %s after %.1f s of mission (%.1f s wall)", status.c_str(), mission_s, wall_s);
    progress(text);
  }
  return result;
}

std::vector<RigPart> all_parts() {
  std::vector<RigPart> parts = rig_parts_outside_ground();
  parts.insert(parts.begin(), RigPart::kGround);
  return parts;
}

// A run's own LCM port on the usual multicast group (the loopback route covers the group, any
// port), so that two runs on one host never hear each other; an explicit URL or
// $LCM_DEFAULT_URL wins.
std::string private_lcm_url(const std::string& requested) {
  if (!requested.empty()) return requested;
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env != nullptr && *env != '\0') return env;
  return "udpm://239.255.76.67:" + std::to_string(7668 + ::getpid() % 20000) + "?ttl=0";
}

int64_t unix_now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

RunResult run_virtual(const Scenario& s, const RunOptions& o, const RigConfigs& cfg, const ProgressFn& progress,
                      const std::atomic<bool>* stop) {
  const auto wall0 = SteadyClock::now();
  const int64_t unix0 = unix_now_us();
  common::VirtualRuntime rt;
  bridge::VirtualCanBus can(rt.scheduler());
  auto can_bridge = can.attach("bridge");
  auto can_fc = can.attach("fc");
  RigNodes n = make_rig_nodes(all_parts(), cfg, o, s, {can_bridge.get(), can_fc.get()}, false);
  for (common::Node* node : n.in_start_order()) rt.add(*node);
  Reporter report{progress};
  std::string status;
  double t = 0.0, dialogue_end_s = -1.0, crash_s = -1.0;
  try {
    while (status.empty()) {
      t += 0.5;
      rt.run_until(static_cast<int64_t>(t * 1e6));
      const RecordedEpisode r = n.recorder->snapshot();
      report(r);
      const bool done = n.conversation->finished();
      if (done && dialogue_end_s < 0.0) dialogue_end_s = t;
      if (r.last_state.crashed && crash_s < 0.0) crash_s = t;
      status = end_reason(r, done, t, dialogue_end_s, crash_s, s.mission.time_limit_s);
      if (status.empty() && stop != nullptr && stop->load()) status = "interrupted";
    }
  } catch (const std::exception& e) {
    status = std::string("node_failed: ") + e.what();
  }
  const double wall = std::chrono::duration<double>(SteadyClock::now() - wall0).count();
  return finish(s, o, n, status, t, wall, unix0, progress);
}

RunResult run_real(const Scenario& s, const RunOptions& o, const RigConfigs& cfg, const ProgressFn& progress,
                   const std::atomic<bool>* stop) {
  const auto wall0 = SteadyClock::now();
  const int64_t unix0 = unix_now_us();
  const std::string can_spec = o.can == "userspace" ? "userspace:a3rig-run-" + std::to_string(::getpid()) : o.can;
  const std::string lcm_url = private_lcm_url(o.lcm_url);
  {
    common::LcmBus probe(lcm_url);
    probe.check_loopback();
  }
  const bool agent_in_thread = o.agent == "llm";
  std::unique_ptr<bridge::CanBus> can_bridge, can_fc;
  std::unique_ptr<RigProcesses> children;
  std::vector<RigPart> in_process = all_parts();
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
  RigNodes n = make_rig_nodes(in_process, cfg, o, s, {can_bridge.get(), can_fc.get()}, agent_in_thread);
  if (progress) progress("LCM: " + lcm_url + "  CAN: " + (can_bridge ? can_bridge->name() : can_spec));
  const common::WallClock clock(o.real_time_factor, common::WallClock::monotonic_now_ns());
  if (children) children->go(clock.epoch_mono_ns());
  std::vector<std::unique_ptr<common::RealTimeNodeThread>> threads;
  for (common::Node* node : n.in_start_order()) {
    threads.push_back(std::make_unique<common::RealTimeNodeThread>(*node, clock, lcm_url));
  }
  for (auto& th : threads) th->start();
  Reporter report{progress};
  std::string status;
  double dialogue_end_s = -1.0, crash_s = -1.0, mission_s = 0.0;
  auto last_line = SteadyClock::now();
  while (status.empty()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    mission_s = clock.now_s();
    const RecordedEpisode r = n.recorder->snapshot();
    report(r);
    for (std::size_t i = 0; i < threads.size() && status.empty(); ++i) {
      if (!threads[i]->failure().empty()) {
        status = "node_failed: " + n.in_start_order()[i]->name() + ": " + threads[i]->failure();
      }
    }
    if (status.empty() && children) {
      if (const std::string why = children->check(); !why.empty()) status = "node_failed: " + why;
    }
    const bool done = n.conversation->finished();
    if (done && dialogue_end_s < 0.0) dialogue_end_s = mission_s;
    if (r.last_state.crashed && crash_s < 0.0) crash_s = mission_s;
    if (status.empty()) status = end_reason(r, done, mission_s, dialogue_end_s, crash_s, s.mission.time_limit_s);
    if (status.empty() && stop != nullptr && stop->load()) status = "interrupted";
    if (progress && SteadyClock::now() - last_line > std::chrono::seconds(10)) {
      last_line = SteadyClock::now();
      const double wall = std::chrono::duration<double>(last_line - wall0).count();
      char text[200];
      std::snprintf(text, sizeof text, "t=%.0f s  z=%.1f m  battery %.0f %%  slice %s  real-time factor %.3f",
                    mission_s, r.last_state.p_W_m[2], r.last_state.battery_pct, r.last_slice.c_str(), mission_s / wall);
      progress(text);
    }
  }
  if (children) children->stop();
  for (auto it = threads.rbegin(); it != threads.rend(); ++it) (*it)->stop_and_join();
  const double wall = std::chrono::duration<double>(SteadyClock::now() - wall0).count();
  return finish(s, o, n, status, mission_s, wall, unix0, progress);
}

}  // namespace

RunResult run_episode(const Scenario& s, const RunOptions& o, const ProgressFn& progress, const std::atomic<bool>* stop) {
  const RigConfigs cfg = make_rig_configs(s, o);
  return o.runtime == Runtime::kVirtual ? run_virtual(s, o, cfg, progress, stop) : run_real(s, o, cfg, progress, stop);
}

}  // namespace a3::rigs
