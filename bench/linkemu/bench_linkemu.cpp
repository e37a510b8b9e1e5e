// CPU cost of the link emulator's parts (Google Benchmark): one per-message decision of
// the link model, one n_t lookup of the network process, and a whole relay through the
// node on the virtual-time runtime (decode, decide, record, queue, deliver, encode).
#include <benchmark/benchmark.h>

#include <vector>

#include "a3lcm/link_message_t.hpp"
#include "common/log.hpp"
#include "common/runtime.hpp"
#include "linkemu/link_emulator_node.hpp"
#include "linkemu/link_transmitter.hpp"
#include "linkemu/synthetic_network.hpp"

namespace a3::linkemu {
namespace {

void BM_TransmitDecision(benchmark::State& state) {
  LinkTransmitter tx(common::RngStreams(1), "up", {});
  NetworkState s;
  s.lat_ms = 14;
  s.jitter_ms = 3;
  s.loss_pct = 0.6;
  s.throughput_mbps = 600;
  int64_t t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tx.transmit(t, 300, s));
    t += 50;
  }
}
BENCHMARK(BM_TransmitDecision);

void BM_NetworkStateAt(benchmark::State& state) {
  SyntheticNetwork network(default_slice_profiles(), common::RngStreams(1), StartRegime::kStationary, 0);
  int64_t t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(network.state_at(Slice::kEmbb, t));
    t += 1000;  // one query per simulated millisecond
  }
}
BENCHMARK(BM_NetworkStateAt);

// Sends batch messages per direction through the node in virtual time, 50 us apart.
class Sender final : public common::Node {
 public:
  explicit Sender(int per_direction) : n_(per_direction) {}
  std::string name() const override { return "sender"; }
  void start(common::Executor& executor, common::Bus& bus) override {
    message_.sender = "bench";
    message_.kind = "mcp_call";
    message_.payload.assign(300, 'x');
    message_.payload_length = 300;
    executor.schedule(0, 50, [this, &executor, &bus] {
      if (sent_ >= n_) return;
      message_.message_id = sent_++;
      message_.utime_us = message_.sent_utime_us = executor.clock().now_us();
      bus.publish(common::channels::kLinkUpTx.of(0), message_);
      bus.publish(common::channels::kLinkDownTx.of(0), message_);
    });
  }

 private:
  int n_;
  int sent_ = 0;
  a3lcm::link_message_t message_{};
};

void BM_RelayVirtualTime(benchmark::State& state) {
  const int per_direction = static_cast<int>(state.range(0));
  for (auto _ : state) {
    LinkEmulatorConfig config;
    config.seed = 1;
    config.net_rate_hz = 0.0;
    config.publish_records = state.range(1) != 0;
    LinkEmulatorNode node(config);
    Sender sender(per_direction);
    common::VirtualRuntime runtime;
    runtime.add(node);
    runtime.add(sender);
    runtime.run_until(static_cast<int64_t>(per_direction) * 50 + 10'000'000);
    if (node.stats().up.received != static_cast<uint64_t>(per_direction)) state.SkipWithError("lost input");
  }
  state.SetItemsProcessed(state.iterations() * per_direction * 2);
  state.SetLabel(state.range(1) ? "messages, with A3_LINK_RECORD" : "messages, no record channel");
}
BENCHMARK(BM_RelayVirtualTime)->Args({100000, 0})->Args({100000, 1})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace a3::linkemu

int main(int argc, char** argv) {
  a3::common::set_log_level(a3::common::LogLevel::kWarn);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
