// Cost of one CAN frame's exact on-wire bit length (CRC-15 and bit stuffing included), per
// frame: the bit-by-bit reference against the table-driven path the virtual CAN bus uses.
// The frames: extended DroneCAN-like frames with random IDs and 0..8 random data bytes.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "bridge/can/frame_bits_reference.hpp"
#include "bridge/can/frame_timing.hpp"

namespace a3::bridge {
namespace {

std::vector<CanFrame> sample_frames() {
  std::mt19937_64 rng(1);
  std::vector<CanFrame> frames(1024);
  for (CanFrame& f : frames) {
    f.id = static_cast<uint32_t>(rng()) & 0x1FFFFFFFu;
    f.size = static_cast<uint8_t>(rng() % 9);
    for (uint8_t& b : f.data) b = static_cast<uint8_t>(rng());
  }
  return frames;
}

template <unsigned (*FrameBits)(const CanFrame&, BitStuffing)>
void frame_bits(benchmark::State& state) {
  const std::vector<CanFrame> frames = sample_frames();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(FrameBits(frames[i], BitStuffing::kExact));
    i = (i + 1) % frames.size();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

void BM_FrameBitsReference(benchmark::State& state) { frame_bits<can_frame_bits_reference>(state); }
void BM_FrameBitsFast(benchmark::State& state) { frame_bits<can_frame_bits>(state); }
BENCHMARK(BM_FrameBitsReference);
BENCHMARK(BM_FrameBitsFast);

}  // namespace
}  // namespace a3::bridge

BENCHMARK_MAIN();
