// Cost of the DroneCAN codec per CAN frame: serialize + split into frames (encode), and
// reassemble + check CRC + deserialize (decode), for single- and multi-frame messages; and
// how fast the virtual CAN bus simulates frames. items_per_second counts frames.
#include <benchmark/benchmark.h>

#include <vector>

#include "bridge/can/virtual_can_bus.hpp"
#include "bridge/dronecan/messages.hpp"
#include "bridge/dronecan/reassembler.hpp"
#include "bridge/dronecan/transfer.hpp"
#include "common/virtual_scheduler.hpp"

namespace a3::bridge {
namespace {

NodeStatus make(NodeStatus*) { return {3600, 0, 0, 0, 0x1234}; }
EscRawCommand make(EscRawCommand*) {
  EscRawCommand m;
  m.cmd = {4000, 4100, 4200, 4300};
  return m;
}
AhrsRawImu make(AhrsRawImu*) {
  AhrsRawImu m;
  m.timestamp.usec = 123456789;
  m.integration_interval = 0.005f;
  m.rate_gyro_latest = {0.01f, -0.02f, 0.5f};
  m.rate_gyro_integral = {5e-5f, -1e-4f, 2.5e-3f};
  m.accelerometer_latest = {0.12f, -0.34f, -9.81f};
  m.accelerometer_integral = {6e-4f, -1.7e-3f, -0.049f};
  m.covariance = {1e-3f, 1e-3f, 1e-3f, 0.05f, 0.05f, 0.05f};
  return m;
}
GnssFix2 make(GnssFix2*) {
  GnssFix2 m;
  m.longitude_deg_1e8 = 854170000;
  m.latitude_deg_1e8 = 4737690000;
  m.height_msl_mm = 410700;
  m.ned_velocity = {1.25f, -0.5f, 0.05f};
  m.sats_used = 14;
  m.status = GnssFix2::kStatus3dFix;
  m.pdop = 1.2f;
  return m;
}
FcStatus make(FcStatus*) {
  FcStatus m;
  m.mode = FcStatus::kModeHold;
  m.armed = true;
  m.p_W_m = {10, 20, 30};
  m.battery_pct = 80;
  return m;
}

template <class Msg>
void BM_Encode(benchmark::State& state) {
  const Msg msg = make(static_cast<Msg*>(nullptr));
  Payload payload;
  std::vector<CanFrame> frames;
  frames.reserve(64);
  uint8_t tid = 0;
  std::size_t per_transfer = 0;
  for (auto _ : state) {
    frames.clear();
    const auto header = message_header<Msg>(42, tid, kPriorityMedium);
    tid = static_cast<uint8_t>((tid + 1) & 31);
    benchmark::DoNotOptimize(append_message_frames(msg, header, payload, frames));
    benchmark::DoNotOptimize(frames.data());
    per_transfer = frames.size();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * per_transfer));
  state.counters["frames/transfer"] = static_cast<double>(per_transfer);
}

template <class Msg>
void BM_Decode(benchmark::State& state) {
  const Msg msg = make(static_cast<Msg*>(nullptr));
  Payload payload;
  std::vector<CanFrame> frames;
  append_message_frames(msg, message_header<Msg>(42, 0), payload, frames);
  DataTypeTable table;
  table.add_message<Msg>();
  TransferReassembler reassembler(table);
  int64_t t = 0;
  for (auto _ : state) {
    ReceivedTransfer transfer;
    for (const CanFrame& frame : frames) reassembler.accept(frame, ++t, transfer);
    Msg decoded;
    benchmark::DoNotOptimize(decode_payload(transfer.payload, transfer.size, decoded));
    benchmark::DoNotOptimize(decoded);
  }
  if (reassembler.stats().rejected_frames() != 0) state.SkipWithError("frames rejected");
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * frames.size()));
  state.counters["frames/transfer"] = static_cast<double>(frames.size());
}

BENCHMARK_TEMPLATE(BM_Encode, NodeStatus);
BENCHMARK_TEMPLATE(BM_Encode, EscRawCommand);
BENCHMARK_TEMPLATE(BM_Encode, FcStatus);
BENCHMARK_TEMPLATE(BM_Encode, GnssFix2);
BENCHMARK_TEMPLATE(BM_Encode, AhrsRawImu);
BENCHMARK_TEMPLATE(BM_Decode, NodeStatus);
BENCHMARK_TEMPLATE(BM_Decode, EscRawCommand);
BENCHMARK_TEMPLATE(BM_Decode, FcStatus);
BENCHMARK_TEMPLATE(BM_Decode, GnssFix2);
BENCHMARK_TEMPLATE(BM_Decode, AhrsRawImu);

// Simulated frames per second of CPU: one sender, two listeners, 8-byte frames.
void BM_VirtualCanBusFrames(benchmark::State& state) {
  common::VirtualScheduler scheduler;
  VirtualCanBus bus(scheduler, {});
  auto sender = bus.attach("sender");
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  uint64_t received = 0;
  a->start(scheduler, [&](const CanFrame&, int64_t) { ++received; });
  b->start(scheduler, [&](const CanFrame&, int64_t) { ++received; });
  CanFrame frame;
  frame.id = 0x1003EB2A;
  frame.size = 8;
  int64_t t = 0;
  for (auto _ : state) {
    for (int i = 0; i < 100; ++i) sender->send(frame);
    t += 20'000;  // 100 frames of ~140 us fit in 20 ms
    scheduler.run_until(t);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * 100));
  benchmark::DoNotOptimize(received);
}
BENCHMARK(BM_VirtualCanBusFrames);

}  // namespace
}  // namespace a3::bridge

BENCHMARK_MAIN();
