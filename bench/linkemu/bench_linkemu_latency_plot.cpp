// The delivered-latency distribution per slice against the SPEC §6 targets. For each
// slice, the link emulator (seeded process, no switching) relays one 200-byte message
// every 5 s of virtual time for 100,000 messages; the records give the delivered latency
// (ingress to delivery) and the n_t latency at send. Prints the figures, writes the CDFs
// (latency_cdf.tsv), a gnuplot script and latency_distribution.png into the output folder.
// Usage: bench_linkemu_latency_plot [OUTPUT_DIR] [MESSAGES_PER_SLICE]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "a3lcm/link_message_t.hpp"
#include "common/log.hpp"
#include "common/runtime.hpp"
#include "linkemu/link_emulator_node.hpp"

namespace a3::linkemu {
namespace {

namespace fs = std::filesystem;
constexpr int64_t kPeriodUs = 5'000'000;

class Sender final : public common::Node {
 public:
  explicit Sender(int n) : n_(n) {}
  std::string name() const override { return "sender"; }
  void start(common::Executor& executor, common::Bus& bus) override {
    message_.sender = "agent";
    message_.kind = "mcp_call";
    message_.payload.assign(200, 'x');
    message_.payload_length = 200;
    executor.schedule(kPeriodUs, kPeriodUs, [this, &executor, &bus] {
      if (sent_ >= n_) return;
      message_.message_id = sent_++;
      message_.utime_us = message_.sent_utime_us = executor.clock().now_us();
      bus.publish(common::channels::kLinkUpTx.of(0), message_);
    });
  }

 private:
  int n_;
  int sent_ = 0;
  a3lcm::link_message_t message_{};
};

struct SliceRun {
  std::vector<double> delivered_ms, nt_lat_ms;
  double hard_share = 0, degraded_share = 0, loss_share = 0;
};

SliceRun run_slice(Slice slice, int messages) {
  LinkEmulatorConfig config;
  config.seed = 2025;
  config.initial_slice = slice;
  config.net_rate_hz = 0.0;
  config.publish_records = false;
  LinkEmulatorNode node(config);
  SliceRun run;
  int hard = 0, degraded = 0, lost = 0;
  node.add_record_sink([&](const a3lcm::link_record_t& r) {
    NetworkState s;
    s.lat_ms = r.net_lat_ms;
    s.loss_pct = r.net_loss_pct;
    s.throughput_mbps = r.net_throughput_mbps;
    s.edge_load = r.net_edge_load;
    hard += is_hard(s);
    degraded += r.net_degraded;
    run.nt_lat_ms.push_back(r.net_lat_ms);
    if (r.outcome == a3lcm::link_record_t::LOST) {
      ++lost;
      return;
    }
    run.delivered_ms.push_back(static_cast<double>(r.delivery_utime_us - r.utime_us) * 1e-3);
  });
  Sender sender(messages);
  common::VirtualRuntime runtime;
  runtime.add(node);
  runtime.add(sender);
  runtime.run_until(static_cast<int64_t>(messages + 2) * kPeriodUs);
  run.hard_share = static_cast<double>(hard) / messages;
  run.degraded_share = static_cast<double>(degraded) / messages;
  run.loss_share = static_cast<double>(lost) / messages;
  std::sort(run.delivered_ms.begin(), run.delivered_ms.end());
  std::sort(run.nt_lat_ms.begin(), run.nt_lat_ms.end());
  return run;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}
double at(const std::vector<double>& sorted, double p) {
  return sorted[static_cast<std::size_t>(p * static_cast<double>(sorted.size() - 1) + 0.5)];
}

int main_impl(int argc, char** argv) {
  const fs::path out_dir = argc > 1 ? fs::path(argv[1]) : fs::path("linkemu_figures");
  const int messages = argc > 2 ? std::atoi(argv[2]) : 100000;
  common::set_log_level(common::LogLevel::kWarn);
  fs::create_directories(out_dir);

  std::vector<SliceRun> runs;
  std::printf("delivered latency (ingress to delivery, 200-byte messages) and n_t latency, per slice, "
              "%d messages 5 s apart\n", messages);
  std::printf("slice | SPEC mean/median/P90 (ms)    | n_t lat mean/median/P90     | delivered mean/median/P90  "
              "| P99 delivered | degraded | hard n_t | lost\n");
  for (Slice slice : kAllSlices) {
    runs.push_back(run_slice(slice, messages));
    const SliceRun& r = runs.back();
    const CorpusTargets& t = default_slice_profiles().at(slice).targets;
    std::printf("%-5s | %6.2f / %6.2f / %6.2f | %6.2f / %6.2f / %6.2f | %6.2f / %6.2f / %6.2f | %9.1f | %7.1f%% | %7.1f%% | %.2f%%\n",
                to_string(slice), t.lat_mean_ms, t.lat_median_ms, t.lat_p90_ms, mean(r.nt_lat_ms),
                at(r.nt_lat_ms, 0.5), at(r.nt_lat_ms, 0.9), mean(r.delivered_ms), at(r.delivered_ms, 0.5),
                at(r.delivered_ms, 0.9), at(r.delivered_ms, 0.99), 100 * r.degraded_share,
                100 * r.hard_share, 100 * r.loss_share);
  }

  std::ofstream tsv(out_dir / "latency_cdf.tsv");
  tsv << "p";
  for (Slice s : kAllSlices) tsv << "\t" << to_string(s) << "_delivered_ms\t" << to_string(s) << "_nt_lat_ms";
  tsv << "\n";
  for (int i = 1; i < 1000; ++i) {
    const double p = i / 1000.0;
    tsv << p;
    for (const SliceRun& r : runs) tsv << "\t" << at(r.delivered_ms, p) << "\t" << at(r.nt_lat_ms, p);
    tsv << "\n";
  }
  tsv.close();

  std::ofstream gp(out_dir / "latency_distribution.gp");
  gp << "# gnuplot script written by bench_linkemu_latency_plot\n"
     << "set terminal pngcairo size 1500,540 font ',11' noenhanced\n"
     << "set output 'latency_distribution.png'\n"
     << "set datafile separator '\\t'\n"
     << "set multiplot layout 1,3 title 'a3rig link emulator: delivered latency per slice against SPEC-alpha3 section 6 (CDF, "
     << messages << " messages per slice, seed 2025)'\n"
     << "set logscale x\nset grid xtics ytics\nset yrange [0:1]\nset ylabel 'fraction of messages'\n"
     << "set xlabel 'latency (ms, log scale)'\nset key at graph 0.98, graph 0.45 right box opaque font ',10' samplen 2\n";
  const char* ticks[] = {"(2, 3, 5, 7, 10, 15, 20, 30)", "(5, 10, 20, 50, 100, 200, 500)",
                         "(5, 10, 20, 50, 100, 200, 500, 1000)"};
  int column = 2;
  for (Slice s : kAllSlices) {
    const CorpusTargets& t = default_slice_profiles().at(s).targets;
    const SliceRun& r = runs[index_of(s)];
    char title[200];
    std::snprintf(title, sizeof title, "%s   (mean ms: SPEC %.2f, n_t %.2f, delivered %.2f)", to_string(s),
                  t.lat_mean_ms, mean(r.nt_lat_ms), mean(r.delivered_ms));
    gp << "set title '" << title << "'\n"
       << "set xtics " << ticks[index_of(s)] << "\n"
       << "set xrange [" << std::max(1.0, at(r.delivered_ms, 0.001) * 0.8) << ":" << at(r.delivered_ms, 0.999) * 1.2 << "]\n"
       << "$targets" << to_string(s) << " << EOD\n"
       << t.lat_median_ms << "\t0.5\n" << t.lat_p90_ms << "\t0.9\nEOD\n"
       << "$mean" << to_string(s) << " << EOD\n"
       << t.lat_mean_ms << "\t0\n" << t.lat_mean_ms << "\t1\nEOD\n"
       << "plot 'latency_cdf.tsv' using " << column << ":1 with lines lw 2 lc rgb '#1f4e9c' title 'delivered', \\\n"
       << "     'latency_cdf.tsv' using " << column + 1 << ":1 with lines lw 1.5 dt 2 lc rgb '#777777' title 'n_t lat_ms', \\\n"
       << "     $targets" << to_string(s) << " using 1:2 with points pt 7 ps 1.6 lc rgb '#cc0000' title 'SPEC median, P90', \\\n"
       << "     $mean" << to_string(s) << " using 1:2 with lines dt 3 lw 1.5 lc rgb '#cc0000' title 'SPEC mean'\n";
    column += 2;
  }
  gp << "unset multiplot\n";
  gp.close();

  const std::string command = "cd '" + fs::absolute(out_dir).string() + "' && gnuplot latency_distribution.gp";
  if (std::system(command.c_str()) != 0) {
    std::printf("gnuplot failed or is missing (apt-get install gnuplot-nox); data in %s\n", out_dir.c_str());
    return 1;
  }
  std::printf("wrote %s\n", (fs::absolute(out_dir) / "latency_distribution.png").c_str());
  return 0;
}

}  // namespace
}  // namespace a3::linkemu

int main(int argc, char** argv) { return a3::linkemu::main_impl(argc, argv); }
