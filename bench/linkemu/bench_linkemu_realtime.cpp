// Real-time figures of the link emulator, on two transports:
//   udpm  loopback LCM multicast, three LCM instances as three processes would have: a
//         sender thread, the node (RealTimeNodeThread), a receiver thread. Every instance
//         reads every packet of the multicast group (LCM filters channels in user space);
//   memq  one LCM instance in one process: the node and a client node (sender + receiver)
//         share the node's real-time executor thread: the node's own relay capacity.
//   1. delivery error: actual minus scheduled delivery time, measured in the node (publish
//      time - scheduled time) and at the receiver (receipt - scheduled, LCM hop included),
//      as is and with every CPU also running a spinning thread; goal p99 <= 0.5 ms;
//   2. sustained relay throughput per direction at increasing offered loads; goal
//      >= 20,000 messages/s per direction.
// Usage: bench_linkemu_realtime [--seconds S] [--rate R] [--busy N] [--no-sweep]
//                               [--sweep-seconds S] [--transport udpm|memq|both] [--rt-priority P]
// The "FIFO" rows run the node's threads SCHED_FIFO at --rt-priority (default 50; 0 skips
// them), as `a3rig node linkemu --rt-priority` does, and a udpm receiver's 10 below it.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "a3lcm/link_message_t.hpp"
#include "common/lcm_bus.hpp"
#include "common/log.hpp"
#include "common/runtime.hpp"
#include "linkemu/link_emulator_node.hpp"
#include "linkemu/realtime_priority.hpp"

namespace a3::linkemu {
namespace {

// The default URL with the largest receive buffer this host allows (net.core.rmem_max).
constexpr const char* kUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

struct Options {
  double seconds = 10.0;        // per delivery-error run
  double rate = 1000.0;         // messages/s per direction in the delivery-error runs
  int busy = static_cast<int>(std::thread::hardware_concurrency());
  bool sweep = true;
  double sweep_seconds = 3.0;
  std::string transport = "both";
  int rt_priority = 50;  // 0: skip the SCHED_FIFO rows
};

struct Quantiles {
  double p50 = 0, p99 = 0, p999 = 0, max = 0;
  std::size_t n = 0;
};

Quantiles quantiles(std::vector<double> v) {
  Quantiles q;
  q.n = v.size();
  if (v.empty()) return q;
  std::sort(v.begin(), v.end());
  const auto at = [&](double p) { return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))]; };
  q.p50 = at(0.5);
  q.p99 = at(0.99);
  q.p999 = at(0.999);
  q.max = v.back();
  return q;
}

// Spinning threads that keep every CPU busy at normal priority.
class BusyLoad {
 public:
  explicit BusyLoad(int threads) {
    for (int i = 0; i < threads; ++i) {
      threads_.emplace_back([this, i] {
        volatile double x = 1.0 + i;
        while (!stop_.load(std::memory_order_relaxed)) {
          for (int k = 0; k < 1000; ++k) x = std::sqrt(x * 1.0000001 + 1.0);
        }
      });
    }
  }
  ~BusyLoad() {
    stop_ = true;
    for (auto& t : threads_) t.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

// memq: sends `rate` messages/s per direction from a 1 ms timer and counts what comes back,
// on the node's own executor.
class ClientNode final : public common::Node {
 public:
  ClientNode(LinkChannels channels, double rate, int64_t start_us, int64_t end_us, bool collect)
      : channels_(std::move(channels)), rate_(rate), start_us_(start_us), end_us_(end_us), collect_(collect) {}
  std::string name() const override { return "client"; }
  void start(common::Executor& executor, common::Bus& bus) override {
    message_.sender = "bench";
    message_.kind = "mcp_call";
    message_.payload.assign(200, 'x');
    message_.payload_length = 200;
    for (const std::string* channel : {&channels_.up_rx, &channels_.down_rx}) {
      const bool up = channel == &channels_.up_rx;
      bus.subscribe_raw(*channel, [this, up](const std::string&, const uint8_t* data, std::size_t size,
                                             int64_t recv_us) {
        ++(up ? got_up : got_down);
        if (!collect_) return;
        a3lcm::link_message_t m;
        if (m.decode(data, 0, static_cast<int>(size)) > 0) errors_us.push_back(static_cast<double>(recv_us - m.utime_us));
      });
    }
    executor.schedule(start_us_, 1000, [this, &executor, &bus] {
      const int64_t now = executor.clock().now_us();
      if (now >= end_us_) return;
      const auto due = static_cast<uint64_t>(static_cast<double>(now - start_us_) * 1e-6 * rate_) + 1;
      for (; sent < due; ++sent) {
        message_.message_id = static_cast<int64_t>(sent);
        message_.utime_us = message_.sent_utime_us = now;
        bus.publish(channels_.up_tx, message_);
        bus.publish(channels_.down_tx, message_);
      }
    });
  }
  uint64_t sent = 0, got_up = 0, got_down = 0;
  std::vector<double> errors_us;

 private:
  LinkChannels channels_;
  double rate_;
  int64_t start_us_, end_us_;
  bool collect_;
  a3lcm::link_message_t message_{};
};

struct RunResult {
  uint64_t sent_per_direction = 0;
  uint64_t node_received = 0;
  uint64_t received_up = 0, received_down = 0;
  double seconds = 0;
  Quantiles node_error_us, receiver_error_us;
};

// A node replaying a constant eMBB vector (20 ms, 4 ms jitter, no loss, 600 Mbps).
LinkEmulatorConfig bench_config() {
  std::mt19937_64 gen(std::random_device{}());
  LinkEmulatorConfig config;
  config.channels = LinkChannels{}.with_suffix("_BENCH" + std::to_string(::getpid()) + "_" +
                                               std::to_string(gen() % 1000000));
  NetworkState s;
  s.slice = Slice::kEmbb;
  s.lat_ms = 20;
  s.jitter_ms = 4;
  s.throughput_mbps = 600;
  s.edge_load = 0.5;
  NetworkTrace trace;
  trace.points.push_back({0, s});
  trace.last_hold_us = 1'000'000;
  config.trace = trace;
  config.publish_records = false;
  config.max_pending_messages = 1'000'000;
  return config;
}

RunResult run_memq(double rate, double seconds, bool collect_errors, int rt_priority) {
  const LinkEmulatorConfig config = bench_config();
  const common::WallClock clock;
  LinkEmulatorNode node(config);
  node.set_lateness_capacity(collect_errors ? 4'000'000 : 0);
  const int64_t start_us = 200'000;
  const auto end_us = start_us + static_cast<int64_t>(seconds * 1e6);
  ClientNode client(config.channels, rate, start_us, end_us, collect_errors);
  std::unique_ptr<common::RealTimeNodeThread> node_thread;
  {
    const ScopedRealtimePriority realtime(rt_priority);
    node_thread = std::make_unique<common::RealTimeNodeThread>(node, clock, "memq://");
    client.start(node_thread->executor(), node_thread->bus());
    node_thread->start();
  }
  common::RealTimeNodeThread& thread = *node_thread;
  while (clock.now_us() < end_us + 300'000) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  thread.stop_and_join();
  RunResult result;
  result.seconds = seconds;
  result.sent_per_direction = client.sent;
  result.node_received = node.stats().up.received + node.stats().down.received;
  result.received_up = client.got_up;
  result.received_down = client.got_down;
  if (collect_errors) {
    const std::vector<float> lateness = node.delivery_lateness_us();
    result.node_error_us = quantiles(std::vector<double>(lateness.begin(), lateness.end()));
    result.receiver_error_us = quantiles(client.errors_us);
  }
  return result;
}

// Sends `rate` messages/s per direction for `seconds` from a sender thread through the node
// thread to a receiver thread, each with its own LCM instance on udpm.
RunResult run_udpm(double rate, double seconds, bool collect_errors, int rt_priority) {
  const LinkEmulatorConfig config = bench_config();
  const common::WallClock clock;
  LinkEmulatorNode node(config);
  node.set_lateness_capacity(collect_errors ? 4'000'000 : 0);
  // With rt_priority > 0 the node's threads (its executor, its LCM receive thread) run
  // SCHED_FIFO at rt_priority, the receiver's at rt_priority - 10 (the link outranks its
  // clients, as in a rig); the sender stays SCHED_OTHER.
  std::optional<ScopedRealtimePriority> realtime(std::in_place, rt_priority);
  common::RealTimeNodeThread node_thread(node, clock, kUrl);
  node_thread.start();
  realtime.emplace(rt_priority > 10 ? rt_priority - 10 : rt_priority);

  RunResult result;
  std::atomic<bool> stop_receiver{false};
  std::vector<double> receiver_error_us;
  receiver_error_us.reserve(collect_errors ? static_cast<std::size_t>(rate * seconds * 2.2) : 0);
  std::atomic<uint64_t> got_up{0}, got_down{0};
  common::LcmBus receiver_bus(kUrl, &clock);
  for (const std::string* channel : {&config.channels.up_rx, &config.channels.down_rx}) {
    const bool up = channel == &config.channels.up_rx;
    receiver_bus.subscribe_raw(*channel, [&, up](const std::string&, const uint8_t* data, std::size_t size,
                                                 int64_t recv_us) {
      (up ? got_up : got_down).fetch_add(1, std::memory_order_relaxed);
      if (!collect_errors) return;
      a3lcm::link_message_t m;
      if (m.decode(data, 0, static_cast<int>(size)) > 0) {
        receiver_error_us.push_back(static_cast<double>(recv_us - m.utime_us));
      }
    });
  }
  std::thread receiver([&] {
    while (!stop_receiver) receiver_bus.handle_timeout(20);
  });

  realtime.reset();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // let the node subscribe

  common::LcmBus sender_bus(kUrl, &clock);
  a3lcm::link_message_t m{};
  m.sender = "bench";
  m.kind = "mcp_call";
  m.payload.assign(200, 'x');
  m.payload_length = 200;
  std::vector<uint8_t> up_bytes, down_bytes;
  const int64_t start_ns = common::WallClock::monotonic_now_ns();
  uint64_t sent = 0;
  const auto total = static_cast<uint64_t>(rate * seconds);
  while (sent < total) {
    const double elapsed_s = static_cast<double>(common::WallClock::monotonic_now_ns() - start_ns) * 1e-9;
    const auto due = std::min<uint64_t>(total, static_cast<uint64_t>(elapsed_s * rate) + 1);
    if (sent >= due) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    for (; sent < due; ++sent) {
      m.message_id = static_cast<int64_t>(sent);
      m.utime_us = m.sent_utime_us = clock.now_us();
      sender_bus.publish(config.channels.up_tx, m);
      sender_bus.publish(config.channels.down_tx, m);
    }
  }
  result.seconds = static_cast<double>(common::WallClock::monotonic_now_ns() - start_ns) * 1e-9;
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let the last ones arrive
  node_thread.stop_and_join();
  stop_receiver = true;
  receiver.join();

  result.sent_per_direction = sent;
  result.node_received = node.stats().up.received + node.stats().down.received;
  result.received_up = got_up;
  result.received_down = got_down;
  if (collect_errors) {
    const std::vector<float> lateness = node.delivery_lateness_us();
    result.node_error_us = quantiles(std::vector<double>(lateness.begin(), lateness.end()));
    result.receiver_error_us = quantiles(receiver_error_us);
  }
  return result;
}

// LCM alone, no link emulator: a sender instance publishes straight to a receiver
// instance on udpm — the ceiling of the transport on this host.
RunResult run_lcm_baseline(double rate, double seconds) {
  common::LcmBus receiver_bus(kUrl);
  std::atomic<uint64_t> got{0};
  const std::string channel = "A3_BENCH_BASELINE_" + std::to_string(::getpid());
  receiver_bus.subscribe_raw(channel, [&](const std::string&, const uint8_t*, std::size_t, int64_t) { ++got; });
  std::atomic<bool> stop{false};
  std::thread receiver([&] {
    while (!stop) receiver_bus.handle_timeout(20);
  });
  common::LcmBus sender_bus(kUrl);
  a3lcm::link_message_t m{};
  m.sender = "bench";
  m.kind = "mcp_call";
  m.payload.assign(200, 'x');
  m.payload_length = 200;
  const int64_t start_ns = common::WallClock::monotonic_now_ns();
  uint64_t sent = 0;
  const auto total = static_cast<uint64_t>(rate * seconds);
  while (sent < total) {
    const double elapsed_s = static_cast<double>(common::WallClock::monotonic_now_ns() - start_ns) * 1e-9;
    const auto due = std::min<uint64_t>(total, static_cast<uint64_t>(elapsed_s * rate) + 1);
    if (sent >= due) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    for (; sent < due; ++sent) sender_bus.publish(channel, m);
  }
  RunResult r;
  r.seconds = static_cast<double>(common::WallClock::monotonic_now_ns() - start_ns) * 1e-9;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  stop = true;
  receiver.join();
  r.sent_per_direction = sent;
  r.received_up = got;
  return r;
}

void print_error_row(const char* transport, const char* load, const RunResult& r) {
  std::printf("%-5s | %-14s | node     | %9zu | %8.1f | %8.1f | %9.1f | %9.1f\n", transport, load,
              r.node_error_us.n, r.node_error_us.p50, r.node_error_us.p99, r.node_error_us.p999,
              r.node_error_us.max);
  std::printf("%-5s | %-14s | receiver | %9zu | %8.1f | %8.1f | %9.1f | %9.1f\n", transport, load,
              r.receiver_error_us.n, r.receiver_error_us.p50, r.receiver_error_us.p99,
              r.receiver_error_us.p999, r.receiver_error_us.max);
}

double load_average() {
  double one = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &one) != 1) one = 0;
    std::fclose(f);
  }
  return one;
}

int main_impl(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> double {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return std::atof(argv[++i]);
    };
    if (a == "--seconds") o.seconds = next();
    else if (a == "--rate") o.rate = next();
    else if (a == "--busy") o.busy = static_cast<int>(next());
    else if (a == "--no-sweep") o.sweep = false;
    else if (a == "--sweep-seconds") o.sweep_seconds = next();
    else if (a == "--transport" && i + 1 < argc) o.transport = argv[++i];
    else if (a == "--rt-priority") o.rt_priority = static_cast<int>(next());
    else {
      std::fprintf(stderr, "usage: %s [--seconds S] [--rate R] [--busy N] [--no-sweep] [--sweep-seconds S] "
                           "[--transport udpm|memq|both] [--rt-priority P]\n", argv[0]);
      return 2;
    }
  }
  common::set_log_level(common::LogLevel::kWarn);
  std::vector<std::string> transports;
  if (o.transport == "memq" || o.transport == "both") transports.push_back("memq");
  if (o.transport == "udpm" || o.transport == "both") {
    try {
      common::LcmBus probe(kUrl);
      probe.check_loopback(1000);
      transports.push_back("udpm");
    } catch (const std::exception& e) {
      std::printf("udpm skipped: LCM over %s does not work on this host: %s\n", kUrl, e.what());
    }
  }
  const auto run = [](const std::string& transport, double rate, double seconds, bool collect, int rt = 0) {
    return transport == "memq" ? run_memq(rate, seconds, collect, rt) : run_udpm(rate, seconds, collect, rt);
  };
  std::printf("link emulator, real time, %u CPUs, load average %.1f at start; udpm URL %s\n\n",
              std::thread::hardware_concurrency(), load_average(), kUrl);
  std::printf("delivery error = actual - scheduled delivery, us (%g msg/s per direction, %g s, 200-byte messages)\n",
              o.rate, o.seconds);
  std::printf("link  | load           | measured | deliveries|      p50 |      p99 |     p99.9 |       max\n");
  for (const std::string& t : transports) {
    print_error_row(t.c_str(), "as is", run(t, o.rate, o.seconds, true));
    BusyLoad busy(o.busy);
    char label[32];
    std::snprintf(label, sizeof label, "+%d spin", o.busy);
    print_error_row(t.c_str(), label, run(t, o.rate, o.seconds, true));
    if (o.rt_priority > 0) {
      std::snprintf(label, sizeof label, "+%d spin, FIFO", o.busy);
      print_error_row(t.c_str(), label, run(t, o.rate, o.seconds, true, o.rt_priority));
    }
  }
  if (!o.sweep) return 0;
  std::printf("\nrelay throughput, both directions at once (%g s per step, 200-byte messages; load average %.1f)\n",
              o.sweep_seconds, load_average());
  std::printf("link  | policy | offered/dir | sent/dir/s | node in/dir/s | delivered up/s | delivered down/s | delivered\n");
  if (std::find(transports.begin(), transports.end(), "udpm") != transports.end()) {
    for (double rate : {10000.0, 20000.0, 40000.0}) {
      const RunResult r = run_lcm_baseline(rate, o.sweep_seconds);
      std::printf("LCM udpm alone, one stream sender -> receiver | offered %6.0f/s | sent %6.0f/s | received %6.0f/s | %5.1f %%\n",
                  rate, static_cast<double>(r.sent_per_direction) / r.seconds,
                  static_cast<double>(r.received_up) / r.seconds,
                  100.0 * static_cast<double>(r.received_up) / static_cast<double>(r.sent_per_direction));
    }
  }
  std::vector<int> policies = {0};
  if (o.rt_priority > 0) policies.push_back(o.rt_priority);
  for (const std::string& t : transports) {
    for (int rt : policies) {
    for (double rate : {10000.0, 20000.0, 40000.0, 60000.0, 80000.0}) {
      const RunResult r = run(t, rate, o.sweep_seconds, false, rt);
      std::printf("%-5s | %-6s | %11.0f | %10.0f | %13.0f | %14.0f | %16.0f | %8.1f %%\n", t.c_str(),
                  rt > 0 ? "FIFO" : "OTHER", rate,
                  static_cast<double>(r.sent_per_direction) / r.seconds,
                  static_cast<double>(r.node_received) / 2.0 / r.seconds,
                  static_cast<double>(r.received_up) / r.seconds,
                  static_cast<double>(r.received_down) / r.seconds,
                  100.0 * static_cast<double>(r.received_up + r.received_down) /
                      static_cast<double>(2 * r.sent_per_direction));
    }
    }
  }
  return 0;
}

}  // namespace
}  // namespace a3::linkemu

int main(int argc, char** argv) { return a3::linkemu::main_impl(argc, argv); }
