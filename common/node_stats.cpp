// Node statistics messages.
#include "common/node_stats.hpp"

#include <unistd.h>

#include <algorithm>

#include "common/node.hpp"

namespace a3::common {
namespace {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

const CounterSet& Node::counters() const {
  static const CounterSet none;
  return none;
}

NamedValues executor_timing(const RealTimeExecutor& executor) {
  const std::vector<double> late = executor.lateness_samples_us();
  return {{"timers_run", static_cast<double>(executor.timers_run())},
          {"lateness_p50_us", percentile(late, 0.50)},
          {"lateness_p99_us", percentile(late, 0.99)},
          {"lateness_max_us", executor.max_lateness_us()},
          {"deadline_misses", static_cast<double>(executor.deadline_misses())}};
}

NamedValues lockstep_timing(const LockstepStats& s) {
  NamedValues timing = {{"lockstep_grants", static_cast<double>(s.grants)},
                        {"lockstep_rounds", static_cast<double>(s.rounds)},
                        {"lockstep_waits", static_cast<double>(s.waits)},
                        {"lockstep_wait_total_s", s.wait_total_s},
                        {"lockstep_wait_max_s", s.wait_max_s},
                        {"lockstep_lag_dropped_s", s.lag_dropped_s},
                        {"achieved_rtf", s.achieved_rtf},
                        {"worst_window_rtf", s.worst_window_rtf},
                        {"wall_s", s.wall_s}};
  for (const auto& [node, held_s] : s.wait_on_s) timing.emplace_back(kLockstepWaitOnPrefix + node + "_s", held_s);
  return timing;
}

a3lcm::node_stats_t make_node_stats(const std::string& node, int64_t utime_us, bool final,
                                    const CounterSet& counters, const NamedValues& timing) {
  a3lcm::node_stats_t m{};
  m.utime_us = utime_us;
  m.wall_utime_us = WallClock::monotonic_now_ns() / 1000;
  m.node = node;
  m.pid = static_cast<int32_t>(::getpid());
  m.is_final = final;
  for (const auto& [name, value] : counters.snapshot()) {
    m.counter_names.push_back(name);
    m.counter_values.push_back(static_cast<int64_t>(value));
  }
  m.n_counters = static_cast<int32_t>(m.counter_names.size());
  for (const auto& [name, value] : timing) {
    m.timing_names.push_back(name);
    m.timing_values.push_back(value);
  }
  m.n_timings = static_cast<int32_t>(m.timing_names.size());
  return m;
}

nlohmann::json node_stats_json(const a3lcm::node_stats_t& m) {
  // Dotted names nest: "up.dropped.queue_full" -> {"up": {"dropped": {"queue_full": n}}}.
  nlohmann::json counters = nlohmann::json::object();
  for (int32_t i = 0; i < m.n_counters; ++i) {
    nlohmann::json* at = &counters;
    std::string_view name = m.counter_names[i];
    for (std::size_t dot; (dot = name.find('.')) != std::string_view::npos; name.remove_prefix(dot + 1)) {
      nlohmann::json& child = (*at)[std::string(name.substr(0, dot))];
      if (!child.is_object()) child = nlohmann::json::object();
      at = &child;
    }
    (*at)[std::string(name)] = m.counter_values[i];
  }
  nlohmann::json out = {{"counters", counters}};
  if (m.n_timings > 0) {
    nlohmann::json timing = nlohmann::json::object();
    for (int32_t i = 0; i < m.n_timings; ++i) timing[m.timing_names[i]] = m.timing_values[i];
    out["timing"] = timing;
  }
  return out;
}

nlohmann::json node_stats_json(const CounterSet& counters, const NamedValues& timing) {
  return node_stats_json(make_node_stats("", 0, true, counters, timing));
}

}  // namespace a3::common
