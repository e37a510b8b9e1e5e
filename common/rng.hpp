// Seeded random-number streams. One master seed per run; each stochastic term (turbulence,
// sensor noise, link latency, loss, ...) draws from its own named stream, so adding a draw
// in one component never shifts another's numbers. The engine is std::mt19937_64 (its
// output is fixed by the C++ standard); the distributions are written here so results are
// identical across standard libraries.
#pragma once

#include <cstdint>
#include <random>
#include <string_view>

namespace a3::common {

class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}

  uint64_t next_u64() { return engine_(); }
  // Uniform in [0, 1), 53 bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  // Normal by the Marsaglia polar method.
  double normal(double mean = 0.0, double stddev = 1.0);
  double lognormal(double mu, double sigma);
  double exponential(double mean);
  bool bernoulli(double p) { return uniform01() < p; }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

// SplitMix64 finaliser: a well-mixed 64-bit hash of x.
uint64_t splitmix64(uint64_t x);

class RngStreams {
 public:
  explicit RngStreams(uint64_t master_seed) : master_seed_(master_seed) {}
  uint64_t master_seed() const { return master_seed_; }
  // Seed of the named stream: splitmix64(master ^ fnv1a64(name)).
  uint64_t stream_seed(std::string_view name) const;
  Rng stream(std::string_view name) const { return Rng(stream_seed(name)); }

 private:
  uint64_t master_seed_;
};

}  // namespace a3::common
