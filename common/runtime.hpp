// The two runtimes of DESIGN.md "Time", for running nodes:
// - VirtualRuntime: every node in one thread under the discrete-event scheduler, on an
//   in-process bus carrying LCM-encoded bytes; as fast as possible, deterministic.
// - RealTimeNodeThread: one node in its own thread with its own LCM bus (udpm:// by default),
//   like a separate process would be, keeping time one of four ways (ThreadClock):
//     wall              the wall clock at a real-time factor (free-running, `--sync free`);
//     lockstep master   a SteppedClock moved by a LockstepPacer on this thread, which grants
//                       time on A3_CLOCK (the dynamics' thread);
//     lockstep follower a SteppedClock moved by the A3_CLOCK grants it hears on its bus,
//                       answering each on A3_CLOCK_ACK when the master waits for it (on
//                       answers_lcm_url, where only the master listens);
//     lockstep external a SteppedClock moved by the node itself from another transport (the
//                       flight controller: a3.sim.Clock frames on CAN).
//   It publishes the node's statistics (node_stats_t on A3_NODE_STATS) every stats period of
//   wall time and once, final, when it stops.
#pragma once

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/clock.hpp"
#include "common/grant_acknowledger.hpp"
#include "common/lcm_bus.hpp"
#include "common/lockstep_pacer.hpp"
#include "common/node.hpp"
#include "common/port_checked_bus.hpp"
#include "common/realtime_executor.hpp"
#include "common/virtual_bus.hpp"
#include "common/virtual_scheduler.hpp"

namespace a3::common {

class VirtualRuntime {
 public:
  VirtualRuntime() : bus_(scheduler_) {}
  // Starts the node on the bus as its ports() allow (port_checked_bus.hpp).
  void add(Node& node) {
    node_buses_.emplace_back();
    node.start(scheduler_, bus_for_node(node, bus_, node_buses_.back()));
  }
  // Runs all nodes until simulated time end_us.
  void run_until(int64_t end_us) { scheduler_.run_until(end_us); }
  VirtualScheduler& scheduler() { return scheduler_; }
  VirtualBus& bus() { return bus_; }
  const Clock& clock() const { return scheduler_.clock(); }

 private:
  VirtualScheduler scheduler_;
  VirtualBus bus_;
  std::vector<std::unique_ptr<Bus>> node_buses_;  // after bus_: they go first
};

struct ThreadClock {
  enum class Kind { kWall, kLockstepMaster, kLockstepFollower, kLockstepExternal };
  Kind kind = Kind::kWall;
  const WallClock* wall = nullptr;  // kWall: shared by every node of the run
  LockstepConfig pacing;            // kLockstepMaster
  bool acknowledges = false;        // kLockstepFollower: answers every grant (GrantAcknowledger)
  double deadline_miss_us = 2000.0;

  static ThreadClock free_running(const WallClock& clock);
  static ThreadClock master(LockstepConfig pacing);
  static ThreadClock follower(bool acknowledges);
  static ThreadClock external();
};

class RealTimeNodeThread {
 public:
  // lcm_url as for LcmBus. The first form runs on a shared wall clock (free-running).
  RealTimeNodeThread(Node& node, const WallClock& clock, const std::string& lcm_url = "");
  RealTimeNodeThread(Node& node, const ThreadClock& how, const std::string& lcm_url = "");
  ~RealTimeNodeThread();
  RealTimeNodeThread(const RealTimeNodeThread&) = delete;
  RealTimeNodeThread& operator=(const RealTimeNodeThread&) = delete;

  // Statistics every period_s of wall time (0: only the final ones). Before start().
  void set_stats_period(double period_s) { stats_period_s_ = period_s; }
  void start();
  void stop_and_join();
  RealTimeExecutor& executor() { return *executor_; }
  LcmBus& bus() { return bus_; }
  const RealTimeClock& clock() const { return *clock_; }
  // The lockstep clock (nullptr when free-running) and pacer (the master only).
  SteppedClock* stepped_clock() { return stepped_.get(); }
  LockstepPacer* pacer() { return pacer_.get(); }
  // The exception that ended the thread, if one did ("" otherwise).
  std::string failure() const;

 private:
  void publish_stats(bool final);

  Node& node_;
  std::unique_ptr<SteppedClock> stepped_;
  const RealTimeClock* clock_;
  LcmBus bus_;
  std::unique_ptr<Bus> node_bus_;  // bus_ as the node's ports() allow
  std::unique_ptr<LcmBus> answers_bus_;  // lockstep: the followers' answers (answers_lcm_url)
  std::unique_ptr<RealTimeExecutor> executor_;
  std::unique_ptr<LockstepPacer> pacer_;
  std::unique_ptr<GrantAcknowledger> acknowledger_;
  double stats_period_s_ = 1.0;
  std::thread thread_;
  mutable std::mutex failure_mutex_;
  std::string failure_;
};

}  // namespace a3::common
