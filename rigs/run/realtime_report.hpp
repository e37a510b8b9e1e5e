// The real-time accounting of an episode (its `_rig.realtime`) and the real-time contract.
// Made from what the nodes published on the bus (node_stats_t) and what the runner measured
// (mission and wall time, the worst 1 s window), it says how real the run was:
//   sync                lockstep | free
//   rtf                 {requested, achieved (whole flight), worst_window (lowest over 1 s of wall)}
//   lockstep            the time master's accounting: grants, waits (grants held past their wall
//                       time for the vehicle's answer), wait_total_s, wait_max_s, lag_dropped_s
//   nodes               per node: timers_run, lateness_p50_us, lateness_p99_us,
//                       lateness_max_us, deadline_misses (timers later than one control period)
//   stale_steps         dynamics steps without a fresh rotor command (never in lockstep)
//   contract            {thresholds, violated, violations: [why]}
// The contract (README "Real time"):
//   lockstep: simulated time is exact whatever the host does (no step passes without the
//     flight controller's output), so a slow host matters only where wall-clock time enters the
//     simulation: an agent whose own latency is measured on the wall clock (--agent llm) is
//     charged at the achieved factor, which must then stay within kLockstepWallAgentTolerance of
//     the requested one over the flight. Agents whose latency is charged in simulated time
//     (scripted, replay, --think-time models) cannot be distorted by the host.
//   free: the whole-flight factor must reach kFreeMinFraction of the requested one, and no node
//     may miss more than kFreeMaxMissFraction of its deadlines (the physics itself was late).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rigs/run/episode_recorder.hpp"
#include "rigs/run/run_options.hpp"

namespace a3::rigs {

inline constexpr double kLockstepWallAgentTolerance = 0.1;
inline constexpr double kFreeMinFraction = 0.9;
inline constexpr double kFreeMaxMissFraction = 0.01;

struct RealTimeMeasure {
  double mission_s = 0.0;
  double wall_s = 0.0;
  double worst_window_rtf = -1.0;  // < 0: the run was shorter than one window
};

nlohmann::json realtime_report(const RunOptions& options, const RealTimeMeasure& measure,
                               const std::map<std::string, NodeStatsRecord>& nodes);
// Whether the run's agent measures its latency on the wall clock (an LLM over HTTP).
bool agent_latency_on_wall_clock(const RunOptions& options);
// The violations listed in a report ("" joined by "; " when none).
std::string realtime_violations(const nlohmann::json& report);

// One line for the run's closing summary: "lockstep, achieved 3.998 of 4 (worst 1 s window
// 3.91), vehicle step lateness p99 0.21 ms, lockstep waits 812 (0.42 s), stale steps 0;
// contract kept".
std::string realtime_summary(const nlohmann::json& report);

// {node: counters} from the nodes' statistics.
nlohmann::json counters_from_stats(const std::map<std::string, NodeStatsRecord>& nodes);

// Tumbling windows of wall time over (wall, simulated) samples: the lowest factor of a whole window.
class WindowMeter {
 public:
  explicit WindowMeter(double window_s = 1.0) : window_s_(window_s) {}
  void sample(double wall_s, double sim_s);
  double worst() const { return worst_; }

 private:
  double window_s_;
  double start_wall_s_ = -1.0, start_sim_s_ = 0.0;
  double worst_ = -1.0;
};

}  // namespace a3::rigs
