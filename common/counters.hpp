// The one way a node counts things (PX4's perf counters): a CounterSet of named counters,
// registered once when the node is built, incremented from the node's thread, read from any
// thread. The runtime publishes every node's set on the bus (node_stats_t on A3_NODE_STATS)
// and the episode's _rig counters are made from those messages, so a node in another process
// is counted exactly as one in this process.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace a3::common {

class Counter {
 public:
  Counter& operator++() {
    value_.fetch_add(1, std::memory_order_relaxed);
    return *this;
  }
  Counter& operator+=(uint64_t n) {
    value_.fetch_add(n, std::memory_order_relaxed);
    return *this;
  }
  // Returns the new value.
  uint64_t add(uint64_t n = 1) { return value_.fetch_add(n, std::memory_order_relaxed) + n; }
  void set(uint64_t v) { value_.store(v, std::memory_order_relaxed); }
  uint64_t value() const { return value_.load(std::memory_order_relaxed); }
  operator uint64_t() const { return value(); }

 private:
  std::atomic<uint64_t> value_{0};
};

class CounterSet {
 public:
  CounterSet() = default;
  CounterSet(const CounterSet&) = delete;
  CounterSet& operator=(const CounterSet&) = delete;

  // Registers a counter (before the node runs); the reference lives as long as the set.
  // Throws std::logic_error for a name registered twice.
  Counter& add(std::string name);
  // The value of a registered counter; throws std::out_of_range naming an unknown one.
  uint64_t get(std::string_view name) const;
  // Every counter, in registration order.
  std::vector<std::pair<std::string, uint64_t>> snapshot() const;

 private:
  std::deque<std::pair<std::string, Counter>> counters_;  // a deque keeps references stable
};

// "name value, name value, ..." for progress lines.
std::string to_text(const CounterSet& counters);

}  // namespace a3::common
