// Who may command the flight controller, and how often its refusals are reported. CAN has no
// authentication (bridge/README.md, "Who may command the vehicle"): the fc obeys a3.fc.Command
// (and, in lockstep, a3.sim.Clock) only from configured source node IDs; a transfer from any
// other node is refused, counted and reported, at most one report per interval so that a node
// that floods the bus with commands cannot flood the episode with events.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/executor.hpp"

namespace a3::bridge {

// The rig's DroneCAN node IDs (`a3rig node fc --node-id`, `a3rig node bridge --node-id`).
inline constexpr uint8_t kDefaultFcNodeId = 10;
inline constexpr uint8_t kDefaultBridgeNodeId = 20;

// Throws std::invalid_argument naming the problem: no source at all, an ID outside 1..127, or
// the fc's own ID (a node never hears its own frames).
void check_command_sources(const std::vector<uint8_t>& sources, uint8_t own_node_id);
bool is_command_source(const std::vector<uint8_t>& sources, uint8_t node_id);
// "20, 21" for messages.
std::string command_sources_text(const std::vector<uint8_t>& sources);

// Reports refusals at a bounded rate: the first at once, then at most one report per interval,
// each covering every refusal since the previous one. Reports run as their own events on the
// executor (never inside the receive handler that counted the refusal).
class RefusalReports {
 public:
  using Report = std::function<void(uint64_t refused_in_report, uint64_t refused_total)>;
  // Throws std::invalid_argument when interval_us is not positive.
  RefusalReports(int64_t interval_us, Report report);
  ~RefusalReports() { stop(); }
  RefusalReports(const RefusalReports&) = delete;
  RefusalReports& operator=(const RefusalReports&) = delete;

  void start(common::Executor& executor) { executor_ = &executor; }
  // Cancels a report that waits (the executor's thread, or after it stopped).
  void stop();
  // Counts a refusal now and schedules its report.
  void record();
  uint64_t total() const { return total_; }

 private:
  void report();

  int64_t interval_us_;
  Report report_;
  common::Executor* executor_ = nullptr;
  int64_t next_report_us_ = INT64_MIN;
  uint64_t waiting_ = 0;
  uint64_t total_ = 0;
  bool scheduled_ = false;
  common::TimerId timer_{};
};

}  // namespace a3::bridge
