// Node statistics on the bus: the node_stats_t message a runtime publishes for each node it
// runs (its CounterSet, its executor's timing and, for the lockstep master, the pacer's
// accounting), and the one JSON form the episode uses for them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "a3lcm/node_stats_t.hpp"
#include "common/counters.hpp"
#include "common/lockstep_pacer.hpp"
#include "common/realtime_executor.hpp"

namespace a3::common {

using NamedValues = std::vector<std::pair<std::string, double>>;

// The timing of a real-time executor: timers_run, lateness_p50_us, lateness_p99_us,
// lateness_max_us, deadline_misses.
NamedValues executor_timing(const RealTimeExecutor& executor);
// The pacer's accounting: lockstep_grants, lockstep_rounds, lockstep_waits, lockstep_wait_total_s,
// lockstep_wait_max_s, lockstep_lag_dropped_s, achieved_rtf, worst_window_rtf, wall_s, and
// lockstep_wait_on_<node>_s for each node whose answer held grants.
NamedValues lockstep_timing(const LockstepStats& stats);
inline constexpr const char* kLockstepWaitOnPrefix = "lockstep_wait_on_";

a3lcm::node_stats_t make_node_stats(const std::string& node, int64_t utime_us, bool final,
                                    const CounterSet& counters, const NamedValues& timing);

// {"counters": {...}, "timing": {...}} (timing omitted when empty); dotted counter names nest.
nlohmann::json node_stats_json(const a3lcm::node_stats_t& stats);
nlohmann::json node_stats_json(const CounterSet& counters, const NamedValues& timing);

}  // namespace a3::common
