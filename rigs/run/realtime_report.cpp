// Real-time accounting.
#include "rigs/run/realtime_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "common/node_stats.hpp"

namespace a3::rigs {
namespace {

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

nlohmann::json timing_of(const NodeStatsRecord& n) {
  return n.stats.contains("timing") ? n.stats["timing"] : nlohmann::json::object();
}

// lockstep_wait_on_<node>_s timings as {node: s}.
nlohmann::json lockstep_waits_by_node(const nlohmann::json& timing) {
  const std::string prefix = common::kLockstepWaitOnPrefix, suffix = "_s";
  nlohmann::json by_node = nlohmann::json::object();
  for (const auto& [key, value] : timing.items()) {
    if (key.size() > prefix.size() + suffix.size() && key.rfind(prefix, 0) == 0 &&
        key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0) {
      by_node[key.substr(prefix.size(), key.size() - prefix.size() - suffix.size())] = value;
    }
  }
  return by_node;
}

// ": fc 1.20 s, tool_server 0.31 s", largest first; "" without a breakdown.
std::string waits_by_node_text(const nlohmann::json& lockstep) {
  if (!lockstep.contains("wait_on_s") || !lockstep["wait_on_s"].is_object()) return "";
  std::vector<std::pair<double, std::string>> waits;
  for (const auto& [node, s] : lockstep["wait_on_s"].items()) waits.emplace_back(s.get<double>(), node);
  std::sort(waits.rbegin(), waits.rend());
  std::string text;
  for (const auto& [s, node] : waits) text += (text.empty() ? ": " : ", ") + node + " " + fixed(s, 2) + " s";
  return text;
}

}  // namespace

void WindowMeter::sample(double wall_s, double sim_s) {
  if (start_wall_s_ < 0.0) {
    start_wall_s_ = wall_s;
    start_sim_s_ = sim_s;
    return;
  }
  if (wall_s - start_wall_s_ < window_s_) return;
  const double rtf = (sim_s - start_sim_s_) / (wall_s - start_wall_s_);
  worst_ = worst_ < 0.0 ? rtf : std::min(worst_, rtf);
  start_wall_s_ = wall_s;
  start_sim_s_ = sim_s;
}

nlohmann::json counters_from_stats(const std::map<std::string, NodeStatsRecord>& nodes) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, n] : nodes) {
    if (n.stats.contains("counters") && !n.stats["counters"].empty()) out[name] = n.stats["counters"];
  }
  return out;
}

bool agent_latency_on_wall_clock(const RunOptions& o) { return o.agent == "llm"; }

nlohmann::json realtime_report(const RunOptions& o, const RealTimeMeasure& m,
                               const std::map<std::string, NodeStatsRecord>& nodes) {
  const double requested = o.real_time_factor;
  const double achieved = m.wall_s > 0.0 ? m.mission_s / m.wall_s : 0.0;
  nlohmann::json per_node = nlohmann::json::object();
  nlohmann::json lockstep = nullptr;
  uint64_t stale_steps = 0;
  std::vector<std::string> violations;
  for (const auto& [name, n] : nodes) {
    nlohmann::json t = timing_of(n);
    nlohmann::json node = nlohmann::json::object();
    for (const char* key : {"timers_run", "lateness_p50_us", "lateness_p99_us", "lateness_max_us", "deadline_misses"}) {
      if (t.contains(key)) node[key] = t[key];
    }
    per_node[name] = node;
    if (t.contains("lockstep_grants")) {
      lockstep = {{"grants", t["lockstep_grants"]},         {"rounds", t.value("lockstep_rounds", 0.0)},
                  {"waits", t["lockstep_waits"]},
                  {"wait_total_s", t["lockstep_wait_total_s"]}, {"wait_max_s", t["lockstep_wait_max_s"]},
                  {"lag_dropped_s", t["lockstep_lag_dropped_s"]}, {"worst_window_rtf", t["worst_window_rtf"]},
                  {"wait_on_s", lockstep_waits_by_node(t)}};
    }
    if (name == "dynamics" && n.stats.contains("counters")) {
      stale_steps = n.stats["counters"].value("stale_steps", uint64_t{0});
    }
    if (o.sync == Sync::kFree) {
      const double run = t.value("timers_run", 0.0), misses = t.value("deadline_misses", 0.0);
      if (run > 0.0 && misses / run > kFreeMaxMissFraction) {
        violations.push_back(name + " missed " + fixed(100.0 * misses / run, 1) + " % of its deadlines (limit " +
                             fixed(100.0 * kFreeMaxMissFraction, 0) + " %)");
      }
    }
  }
  nlohmann::json thresholds = nlohmann::json::object();
  const bool wall_agent = agent_latency_on_wall_clock(o);
  if (o.sync == Sync::kLockstep && wall_agent) {
    thresholds["max_achieved_deviation_fraction"] = kLockstepWallAgentTolerance;
    if (m.wall_s > 0.0 && std::abs(achieved - requested) > kLockstepWallAgentTolerance * requested) {
      violations.insert(violations.begin(),
                        "achieved real-time factor " + fixed(achieved, 3) + " is more than " +
                            fixed(100.0 * kLockstepWallAgentTolerance, 0) + " % off the requested " +
                            fixed(requested, 3) + ", and the agent's latency is measured on the wall clock");
    }
  } else if (o.sync == Sync::kFree) {
    thresholds["min_achieved_fraction"] = kFreeMinFraction;
    thresholds["max_deadline_miss_fraction"] = kFreeMaxMissFraction;
    if (m.wall_s > 0.0 && achieved < kFreeMinFraction * requested) {
      violations.insert(violations.begin(), "achieved real-time factor " + fixed(achieved, 3) + " below " +
                                                fixed(kFreeMinFraction, 2) + " x the requested " + fixed(requested, 3));
    }
  }
  return {{"sync", to_string(o.sync)},
          {"rtf", {{"requested", requested}, {"achieved", achieved}, {"worst_window", m.worst_window_rtf}}},
          {"lockstep", lockstep},
          {"nodes", per_node},
          {"stale_steps", stale_steps},
          {"contract", {{"thresholds", thresholds}, {"violated", !violations.empty()}, {"violations", violations}}}};
}

std::string realtime_summary(const nlohmann::json& r) {
  const nlohmann::json& rtf = r["rtf"];
  double p99_us = 0.0;
  for (const char* node : {"dynamics", "bridge", "fc"}) {
    if (r["nodes"].contains(node)) p99_us = std::max(p99_us, r["nodes"][node].value("lateness_p99_us", 0.0));
  }
  std::string line = r.value("sync", "?") + ", achieved " + fixed(rtf.value("achieved", 0.0), 3) + " of " +
                     fixed(rtf.value("requested", 0.0), 3) + " (worst 1 s window " +
                     fixed(rtf.value("worst_window", -1.0), 2) + "), vehicle step lateness p99 " +
                     fixed(p99_us * 1e-3, 2) + " ms";
  if (r["lockstep"].is_object()) {
    line += ", lockstep waits " + fixed(r["lockstep"].value("waits", 0.0), 0) + " (" +
            fixed(r["lockstep"].value("wait_total_s", 0.0), 2) + " s" + waits_by_node_text(r["lockstep"]) + ")";
  }
  line += ", stale steps " + std::to_string(r.value("stale_steps", uint64_t{0})) + "; contract ";
  const std::string why = realtime_violations(r);
  return line + (why.empty() ? "kept" : "broken: " + why);
}

std::string realtime_violations(const nlohmann::json& report) {
  std::string out;
  if (!report.is_object() || !report.contains("contract")) return out;
  for (const auto& v : report["contract"].value("violations", nlohmann::json::array())) {
    out += (out.empty() ? "" : "; ") + v.get<std::string>();
  }
  return out;
}

}  // namespace a3::rigs
