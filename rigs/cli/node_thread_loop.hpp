// What every `a3rig node ...` command shares: the pacing flags (--rtf, --duration-s,
// --report-every-s) and --lcm-url, each written once, and the foreground loop of a node that
// runs in a RealTimeNodeThread: start it, report every so often, stop on Ctrl-C/SIGTERM, a node
// failure or the end of the asked duration. (An exception from a command's body reaches
// main(), which prints it and exits 2, as for every command.)
#pragma once

#include <CLI/CLI.hpp>

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "common/clock.hpp"
#include "common/runtime.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/signal_stop.hpp"

namespace a3::rigs {

struct NodePacing {
  double rtf = 1.0;             // simulated seconds per wall second
  double duration_s = 0.0;      // simulated seconds before the command ends; 0: until stopped
  double report_every_s = 5.0;  // wall seconds between status lines on stderr
};

// --rtf (also spelled --real-time-factor) and --duration-s; --report-every-s when the command
// prints status lines.
inline void add_node_pacing_flags(CLI::App& cmd, NodePacing& pacing, bool reports = true) {
  cmd.add_option("--rtf,--real-time-factor", pacing.rtf, "real-time factor: simulated seconds per wall second (default 1)")
      ->check(positive());
  cmd.add_option("--duration-s", pacing.duration_s, "stop after this much simulated time (default: run until stopped)")
      ->check(non_negative());
  if (reports) {
    cmd.add_option("--report-every-s", pacing.report_every_s, "status line period on stderr, wall seconds (default 5)")
        ->check(positive());
  }
}

inline void add_lcm_url_flag(CLI::App& cmd, std::string& lcm_url) {
  cmd.add_option("--lcm-url", lcm_url, "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
}

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
