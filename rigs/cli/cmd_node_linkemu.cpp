// `a3rig node linkemu`: runs the link emulator node on its own in real time, on LCM
// (linkemu/README.md): relays A3_LINK_{UP,DOWN}_TX to _RX with the active 6G slice's
// timing and loss, publishes A3_NET, answers slice switches and edge-compute requests,
// and optionally writes one JSON line per message. Also prints or refits slice profiles.
#include <CLI/CLI.hpp>

#include <signal.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "common/log.hpp"
#include "common/runtime.hpp"
#include "linkemu/link_emulator_config.hpp"
#include "linkemu/link_emulator_node.hpp"
#include "linkemu/link_record_log.hpp"
#include "linkemu/profile_fit.hpp"
#include "linkemu/realtime_priority.hpp"
#include "linkemu/slice_profile.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/node_thread_loop.hpp"

namespace a3::rigs {
namespace {

struct LinkemuArgs {
  std::string config;
  std::string profiles;
  std::optional<uint64_t> seed;
  std::string slice;
  std::string trace;
  std::optional<double> trace_period_s;
  bool trace_loop = false;
  std::optional<double> net_rate_hz;
  std::optional<double> handover_ms;
  bool reorder = false;
  std::optional<double> ge_burst;
  std::optional<double> ge_loss_in_bad;
  std::string start_regime;
  std::optional<double> degraded_share;
  std::optional<double> degraded_dwell_s;
  std::string records;
  bool no_record_channel = false;
  std::string channel_suffix;
  std::string lcm_url;
  NodePacing pacing;  // --rtf, --duration-s (no status lines: --stats-every-s)
  int64_t clock_epoch_mono_ns = -1;
  double stats_every_s = 10.0;
  int rt_priority = 0;
  bool print_profiles = false;
  bool fit_profiles = false;
};

// Rounds every number in a JSON document to `digits` significant digits (for files people read).
void round_numbers(nlohmann::ordered_json& value, int digits) {
  if (value.is_number_float()) {
    const double x = value.get<double>();
    if (x != 0.0 && std::isfinite(x)) {
      const double scale = std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::abs(x)))));
      value = std::round(x * scale) / scale;
    }
  } else if (value.is_structured()) {
    for (auto& item : value) round_numbers(item, digits);
  }
}

linkemu::SliceProfiles read_profiles(const LinkemuArgs& args) {
  return args.profiles.empty() ? linkemu::default_slice_profiles()
                               : linkemu::load_slice_profiles(args.profiles);
}

linkemu::LinkEmulatorConfig build_config(const LinkemuArgs& args) {
  linkemu::LinkEmulatorConfig c =
      args.config.empty() ? linkemu::LinkEmulatorConfig{}
                          : linkemu::load_link_emulator_config(args.config);
  if (args.seed) c.seed = *args.seed;
  if (!args.slice.empty()) c.initial_slice = linkemu::parse_slice(args.slice);
  if (!args.slice.empty() && (c.trace || !args.trace.empty())) {
    common::log_warn("linkemu", "--slice is ignored: a trace decides the slice");
  }
  if (!args.start_regime.empty()) c.start_regime = linkemu::parse_start_regime(args.start_regime);
  if (args.degraded_share) c.degraded_share = *args.degraded_share;
  if (args.degraded_dwell_s) c.degraded_dwell_mean_s = *args.degraded_dwell_s;
  if (!args.trace.empty()) {
    c.trace = linkemu::load_network_trace(
        args.trace, args.trace_period_s.value_or(linkemu::kDefaultTracePeriodS));
  }
  if (args.trace_loop) c.trace_loop = true;
  if (args.net_rate_hz) c.net_rate_hz = *args.net_rate_hz;
  if (args.handover_ms) c.handover_delay_ms = *args.handover_ms;
  if (args.reorder) c.link.reordering = true;
  if (args.ge_burst || args.ge_loss_in_bad) {
    c.link.gilbert_elliott.enabled = true;
    if (args.ge_burst) c.link.gilbert_elliott.mean_burst_messages = *args.ge_burst;
    if (args.ge_loss_in_bad) c.link.gilbert_elliott.loss_in_bad = *args.ge_loss_in_bad;
  }
  if (args.no_record_channel) c.publish_records = false;
  if (!args.channel_suffix.empty()) c.channels = c.channels.with_suffix(args.channel_suffix);
  linkemu::validate(c);
  return c;
}

double quantile(std::vector<float> values, double p) {
  if (values.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(p * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

std::string lateness_summary(const std::vector<float>& lateness_us) {
  if (lateness_us.empty()) return "no deliveries";
  char line[160];
  std::snprintf(line, sizeof line, "delivery error (publish - scheduled) p50 %.1f us, p99 %.1f us, max %.1f us over the last %zu deliveries",
                quantile(lateness_us, 0.5), quantile(lateness_us, 0.99),
                *std::max_element(lateness_us.begin(), lateness_us.end()), lateness_us.size());
  return line;
}

int run_linkemu(const LinkemuArgs& args) {
  const linkemu::SliceProfiles profiles = read_profiles(args);
  if (args.fit_profiles || args.print_profiles) {
    nlohmann::ordered_json document =
        linkemu::to_json(args.fit_profiles ? linkemu::fit_slice_profiles(profiles) : profiles);
    if (args.fit_profiles) round_numbers(document, 6);
    std::cout << document.dump(2) << "\n";
    return 0;
  }
  const linkemu::LinkEmulatorConfig config = build_config(args);

  // SIGINT / SIGTERM end the run: blocked here (and so in the node's thread), taken by sigtimedwait.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  const common::WallClock clock(args.pacing.rtf, args.clock_epoch_mono_ns);
  linkemu::LinkEmulatorNode node(config, profiles);
  std::unique_ptr<linkemu::LinkRecordLog> log;
  if (!args.records.empty()) {
    log = std::make_unique<linkemu::LinkRecordLog>(args.records);
    node.add_record_sink([&log](const a3lcm::link_record_t& r) { log->write(r); });
  }
  std::unique_ptr<common::RealTimeNodeThread> node_thread;
  {
    // Threads created in this scope (LCM's receive thread, the executor's) run SCHED_FIFO.
    const linkemu::ScopedRealtimePriority realtime(args.rt_priority);
    node_thread = std::make_unique<common::RealTimeNodeThread>(node, clock, args.lcm_url);
    if (node_thread->bus().url().rfind("udpm://", 0) == 0) node_thread->bus().check_loopback(1000);
    if (args.stats_every_s > 0.0) {
      const auto period_us = static_cast<int64_t>(args.stats_every_s * 1e6);
      node_thread->executor().schedule_every(period_us, [&node] {
        common::log_info("linkemu", linkemu::summary(node.stats()));
      });
    }
    std::fprintf(stderr, "a3rig node linkemu: on %s, %s%s; Ctrl-C to stop\n",
                 node_thread->bus().url().c_str(), node.describe_source().c_str(),
                 args.rt_priority > 0 ? (", SCHED_FIFO " + std::to_string(args.rt_priority)).c_str() : "");
    node_thread->start();
  }
  common::RealTimeNodeThread& thread = *node_thread;

  const double wall_limit_s = args.pacing.duration_s > 0.0 ? args.pacing.duration_s / args.pacing.rtf : 0.0;
  const int64_t start_ns = common::WallClock::monotonic_now_ns();
  for (;;) {
    timespec wait{0, 200'000'000};
    const int signal_number = sigtimedwait(&stop_signals, nullptr, &wait);
    if (signal_number == SIGINT || signal_number == SIGTERM) break;
    if (!thread.failure().empty()) break;
    const double elapsed_s = static_cast<double>(common::WallClock::monotonic_now_ns() - start_ns) * 1e-9;
    if (wall_limit_s > 0.0 && elapsed_s >= wall_limit_s) break;
  }
  thread.stop_and_join();
  if (log) log->close();

  std::fprintf(stderr, "a3rig node linkemu: %s\n", linkemu::summary(node.stats()).c_str());
  std::fprintf(stderr, "a3rig node linkemu: %s\n", lateness_summary(node.delivery_lateness_us()).c_str());
  if (log) {
    std::fprintf(stderr, "a3rig node linkemu: %llu records written to %s\n",
                 static_cast<unsigned long long>(log->lines()), args.records.c_str());
  }
  if (!thread.failure().empty()) {
    std::fprintf(stderr, "a3rig node linkemu: the node stopped: %s\n", thread.failure().c_str());
    return 1;
  }
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("50-node-linkemu", [](CLI::App& app) {
  auto args = std::make_shared<LinkemuArgs>();
  CLI::App* node = app.get_subcommand("node");
  CLI::App* cmd = node->add_subcommand(
      "linkemu",
      "Run the 6G link emulator in real time on LCM: relays A3_LINK_UP_TX -> A3_LINK_UP_RX and "
      "A3_LINK_DOWN_TX -> A3_LINK_DOWN_RX with the active slice's latency, jitter, loss and "
      "throughput; publishes n_t on A3_NET; switches slices on A3_SLICE_REQ; answers "
      "edge-compute requests on A3_EDGE_REQ. Stops on Ctrl-C / SIGTERM or after --duration-s. "
      "Command-line options override --config. See linkemu/README.md.");
  cmd->add_option("--config", args->config, "link emulator settings (JSON, see linkemu/README.md)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--profiles", args->profiles, "slice profiles (JSON; default: the compiled-in SPEC §6 fit)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--seed", args->seed, "master seed of the network-state process and the per-message draws");
  cmd->add_option("--slice", args->slice, "initial slice: URLLC, eMBB (default) or mMTC")
      ->check(CLI::IsMember(linkemu::slice_names()));
  cmd->add_option("--start-regime", args->start_regime,
                  "regime at start: stationary (default), normal or degraded")
      ->check(CLI::IsMember({"stationary", "normal", "degraded"}));
  cmd->add_option("--degraded-dwell-s", args->degraded_dwell_s,
                  "mean length of a degraded episode, s (keeps each slice's degraded share)")
      ->check(a3::rigs::positive());
  cmd->add_option("--degraded-share", args->degraded_share,
                  "share of time degraded on every slice, [0, 1) (a stress setting: time averages "
                  "then differ from SPEC §6)")
      ->check(a3::rigs::between(0.0, 0.999));
  cmd->add_option("--trace", args->trace,
                  "replay n_t from a trace: a JSON list of points, {\"trace\": [...]}, or an "
                  "α³-Bench episode (its turns' net vectors)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--trace-period-s", args->trace_period_s,
                  "spacing of trace points without t_s, e.g. episode turns (default 5)")
      ->check(a3::rigs::positive());
  cmd->add_flag("--trace-loop", args->trace_loop, "start the trace over at its end (default: hold the last point)");
  cmd->add_option("--net-rate-hz", args->net_rate_hz, "A3_NET publication rate (default 10; 0: on change only)")
      ->check(a3::rigs::between(0.0, 10000.0));
  cmd->add_option("--handover-ms", args->handover_ms, "slice-switch handover delay, ms (default 100)")
      ->check(a3::rigs::non_negative());
  cmd->add_flag("--reorder", args->reorder, "let jitter reorder messages (default: FIFO per direction)");
  cmd->add_option("--ge-burst", args->ge_burst,
                  "Gilbert-Elliott bursty loss: mean burst length in messages (enables it)")
      ->check(a3::rigs::between(1.0, 1e9));
  cmd->add_option("--ge-loss-in-bad", args->ge_loss_in_bad,
                  "Gilbert-Elliott: loss probability in the Bad state (default 0.5; enables it)")
      ->check(a3::rigs::between(0.0, 1.0));
  cmd->add_option("--records", args->records, "write one JSON line per message to this file");
  cmd->add_flag("--no-record-channel", args->no_record_channel,
                "do not publish link_record_t on A3_LINK_RECORD");
  cmd->add_option("--channel-suffix", args->channel_suffix, "append this to every channel name");
  add_lcm_url_flag(*cmd, args->lcm_url);
  add_node_pacing_flags(*cmd, args->pacing, false);
  cmd->add_option("--clock-epoch-mono-ns", args->clock_epoch_mono_ns,
                  "CLOCK_MONOTONIC instant of simulated time 0, shared by every node of a run (default: now)");
  cmd->add_option("--stats-every-s", args->stats_every_s, "log the counters this often (default 10; 0: never)")
      ->check(a3::rigs::non_negative());
  cmd->add_option("--rt-priority", args->rt_priority,
                  "run the node's threads SCHED_FIFO at this priority (1-99; needs root or "
                  "CAP_SYS_NICE): keeps deliveries on time when the CPUs are busy (default 0: off)")
      ->check(a3::rigs::between(0, 99));
  cmd->add_flag("--print-profiles", args->print_profiles, "print the slice profiles in use (JSON) and exit");
  cmd->add_flag("--fit-profiles", args->fit_profiles,
                "refit the profiles' fitted fields to their SPEC §6 targets, print the JSON and exit");
  cmd->callback([args] { command_exit_status() = run_linkemu(*args); });
});

}  // namespace a3::rigs
