// The foreground loop of an `a3rig node ...` command whose node runs in a RealTimeNodeThread:
// start it, report every so often, stop on Ctrl-C/SIGTERM, a node failure or the end of the
// asked duration.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "common/clock.hpp"
#include "common/runtime.hpp"
#include "rigs/cli/signal_stop.hpp"

namespace a3::rigs {

// Starts `thread`, calls report(simulated s) every report_every_s of wall time and once at the
// end of duration_s simulated seconds (0: no end), and stops and joins the thread when a stop
// signal comes, the node fails or the duration is over. Returns the node's failure, "" if none.
inline std::string run_node_thread(common::RealTimeNodeThread& thread, const common::WallClock& clock,
                                   double duration_s, double report_every_s,
                                   const std::function<void(double sim_s)>& report) {
  install_stop_signals();
  thread.start();
  int64_t last_report_ns = common::WallClock::monotonic_now_ns();
  while (!stop_requested() && thread.failure().empty()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const double sim_s = clock.now_s();
    const int64_t now_ns = common::WallClock::monotonic_now_ns();
    const bool done = duration_s > 0 && sim_s >= duration_s;
    if ((now_ns - last_report_ns) * 1e-9 >= report_every_s || done) {
      report(sim_s);
      last_report_ns = now_ns;
    }
    if (done) break;
  }
  thread.stop_and_join();
  return thread.failure();
}

}  // namespace a3::rigs
