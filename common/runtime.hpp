// The two runtimes of DESIGN.md "Time", for running nodes:
// - VirtualRuntime: every node in one thread under the discrete-event scheduler, on an
//   in-process bus carrying LCM-encoded bytes; as fast as possible, deterministic.
// - RealTimeNodeThread: one node in its own thread on the wall clock, with its own LCM bus
//   (udpm:// by default), like a separate process would be.
#pragma once

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/clock.hpp"
#include "common/lcm_bus.hpp"
#include "common/node.hpp"
#include "common/realtime_executor.hpp"
#include "common/virtual_bus.hpp"
#include "common/virtual_scheduler.hpp"

namespace a3::common {

class VirtualRuntime {
 public:
  VirtualRuntime() : bus_(scheduler_) {}
  void add(Node& node) { node.start(scheduler_, bus_); }
  // Runs all nodes until simulated time end_us.
  void run_until(int64_t end_us) { scheduler_.run_until(end_us); }
  VirtualScheduler& scheduler() { return scheduler_; }
  VirtualBus& bus() { return bus_; }
  const Clock& clock() const { return scheduler_.clock(); }

 private:
  VirtualScheduler scheduler_;
  VirtualBus bus_;
};

class RealTimeNodeThread {
 public:
  // The clock is shared by every node of a run; lcm_url as for LcmBus.
  RealTimeNodeThread(Node& node, const WallClock& clock, const std::string& lcm_url = "");
  ~RealTimeNodeThread();
  RealTimeNodeThread(const RealTimeNodeThread&) = delete;
  RealTimeNodeThread& operator=(const RealTimeNodeThread&) = delete;

  void start();
  void stop_and_join();
  RealTimeExecutor& executor() { return executor_; }
  LcmBus& bus() { return bus_; }
  // The exception that ended the thread, if one did ("" otherwise).
  std::string failure() const;

 private:
  Node& node_;
  LcmBus bus_;
  RealTimeExecutor executor_;
  std::thread thread_;
  mutable std::mutex failure_mutex_;
  std::string failure_;
};

}  // namespace a3::common
