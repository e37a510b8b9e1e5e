// RngStreams and Rng: reproducible named streams, pinned first values (a change of engine,
// hash or seeding breaks these on purpose), and the distributions' statistics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "common/rng.hpp"

namespace a3::common {
namespace {

TEST(RngStreams, SameSeedAndNameGiveIdenticalSequences) {
  const RngStreams a(42), b(42);
  Rng ra = a.stream("turbulence");
  Rng rb = b.stream("turbulence");
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(ra.next_u64(), rb.next_u64()) << "draw " << i;
  }
  // Mixed draws too (normal() keeps a spare value between calls).
  Rng na = a.stream("sensor_noise");
  Rng nb = b.stream("sensor_noise");
  for (int i = 0; i < 1001; ++i) {
    ASSERT_EQ(na.normal(1.0, 2.0), nb.normal(1.0, 2.0)) << "draw " << i;
    ASSERT_EQ(na.uniform01(), nb.uniform01()) << "draw " << i;
  }
}

TEST(RngStreams, DifferentNamesOrSeedsGiveDifferentSequences) {
  const RngStreams streams(42);
  const std::vector<std::string> names = {"turbulence", "sensor_noise", "link_latency",
                                          "link_loss",  "turbulenc",    "turbulencf", ""};
  std::set<uint64_t> seeds;
  std::set<uint64_t> firsts;
  for (const auto& name : names) {
    seeds.insert(streams.stream_seed(name));
    firsts.insert(streams.stream(name).next_u64());
  }
  EXPECT_EQ(seeds.size(), names.size()) << "stream seeds collide";
  EXPECT_EQ(firsts.size(), names.size()) << "first draws collide";
  EXPECT_NE(RngStreams(42).stream_seed("turbulence"), RngStreams(43).stream_seed("turbulence"));
  EXPECT_EQ(RngStreams(7).master_seed(), 7u);

  // Two streams are not shifted copies of each other.
  Rng a = streams.stream("link_latency");
  Rng b = streams.stream("link_loss");
  std::vector<uint64_t> va, vb;
  for (int i = 0; i < 64; ++i) {
    va.push_back(a.next_u64());
    vb.push_back(b.next_u64());
  }
  for (uint64_t x : va) {
    for (uint64_t y : vb) ASSERT_NE(x, y);
  }
}

TEST(RngStreams, DrawingFromOneStreamDoesNotShiftAnother) {
  const RngStreams streams(2024);
  Rng alone = streams.stream("link_loss");
  const uint64_t expected = alone.next_u64();
  Rng busy = streams.stream("turbulence");
  for (int i = 0; i < 10000; ++i) busy.next_u64();
  EXPECT_EQ(streams.stream("link_loss").next_u64(), expected);
}

// Published reference values, independent of this code.
TEST(RngPinned, Splitmix64MatchesTheReferenceImplementation) {
  // First output of Vigna's splitmix64 with state 0.
  EXPECT_EQ(splitmix64(0), 0xE220A8397B1DCDAFULL);
}

TEST(RngPinned, EngineIsTheStandardMt19937_64) {
  // [rand.predef]: the 10000th output of a default-seeded (5489) mt19937_64.
  Rng rng(5489);
  uint64_t x = 0;
  for (int i = 0; i < 10000; ++i) x = rng.next_u64();
  EXPECT_EQ(x, 9981545732273789042ULL);
}

TEST(RngPinned, StreamSeedIsSplitmixOfMasterXorFnv1a) {
  // FNV-1a 64 of "" is the offset basis, of "a" is 0xaf63dc4c8601ec8c: a master seed equal
  // to it cancels the hash, leaving splitmix64(0).
  EXPECT_EQ(RngStreams(0xCBF29CE484222325ULL).stream_seed(""), 0xE220A8397B1DCDAFULL);
  EXPECT_EQ(RngStreams(0xAF63DC4C8601EC8CULL).stream_seed("a"), 0xE220A8397B1DCDAFULL);
}

// Computed once from this implementation and pinned: if these change, every seeded result
// of the rig (turbulence, noise, link timing) changes with them.
TEST(RngPinned, FirstValuesOfNamedStreams) {
  const RngStreams streams(42);
  EXPECT_EQ(streams.stream_seed("turbulence"), 0x3DCB47D75A28D3CEULL);
  Rng turbulence = streams.stream("turbulence");
  EXPECT_EQ(turbulence.next_u64(), 0x726B5CA272681B3AULL);
  EXPECT_EQ(turbulence.next_u64(), 0xC2F4F7DAAADDA8E0ULL);
  EXPECT_EQ(turbulence.next_u64(), 0x12BE0079513CDB3DULL);

  Rng latency = streams.stream("link_latency");
  EXPECT_DOUBLE_EQ(latency.uniform01(), 0.47184817219224939);
  EXPECT_DOUBLE_EQ(latency.normal(), -0.24021816782200606);
  EXPECT_DOUBLE_EQ(latency.normal(), 1.3723680461576642);  // the polar method's spare
  EXPECT_DOUBLE_EQ(latency.exponential(2.0), 1.5231777672907554);
}

TEST(Rng, Uniform01IsInTheHalfOpenUnitIntervalAndFlat) {
  Rng rng(1);
  constexpr int kN = 1'000'000;
  constexpr int kBins = 20;
  std::vector<int> bins(kBins, 0);
  double sum = 0.0, lo = 1.0, hi = 0.0;
  for (int i = 0; i < kN; ++i) {
    const double u = rng.uniform01();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    ++bins[static_cast<int>(u * kBins)];
  }
  EXPECT_NEAR(sum / kN, 0.5, 0.003);  // sd of the mean 0.00029
  EXPECT_LT(lo, 1e-4);
  EXPECT_GT(hi, 1.0 - 1e-4);
  // Chi-square with 19 degrees of freedom: 60 is far beyond the 99.999th percentile.
  double chi2 = 0.0;
  const double expected = static_cast<double>(kN) / kBins;
  for (int count : bins) chi2 += (count - expected) * (count - expected) / expected;
  EXPECT_LT(chi2, 60.0);
}

TEST(Rng, UniformAndBernoulli) {
  Rng rng(2);
  int hits = 0;
  for (int i = 0; i < 200'000; ++i) {
    const double x = rng.uniform(-3.0, 5.0);
    ASSERT_GE(x, -3.0);
    ASSERT_LT(x, 5.0);
    if (rng.bernoulli(0.3)) ++hits;
  }
  EXPECT_NEAR(hits / 200'000.0, 0.3, 0.005);  // sd 0.001
  Rng edge(3);
  for (int i = 0; i < 1000; ++i) {
    ASSERT_FALSE(edge.bernoulli(0.0));
    ASSERT_TRUE(edge.bernoulli(1.0));
  }
}

TEST(Rng, NormalHasTheRequestedMeanAndStddev) {
  Rng rng(3);
  constexpr int kN = 400'000;
  const double mean = 5.0, stddev = 2.0;
  double sum = 0.0, sum_sq = 0.0;
  int within_one_sd = 0;
  for (int i = 0; i < kN; ++i) {
    const double x = rng.normal(mean, stddev);
    ASSERT_TRUE(std::isfinite(x));
    sum += x;
    sum_sq += x * x;
    if (std::abs(x - mean) < stddev) ++within_one_sd;
  }
  const double m = sum / kN;
  const double sd = std::sqrt(sum_sq / kN - m * m);
  EXPECT_NEAR(m, mean, 0.02);        // sd of the mean 0.0032
  EXPECT_NEAR(sd, stddev, 0.02);     // sd of the sd ~0.0022
  // Shape, not just moments: 68.27 % within one standard deviation.
  EXPECT_NEAR(static_cast<double>(within_one_sd) / kN, 0.6827, 0.005);
}

TEST(Rng, ExponentialHasTheRequestedMeanAndIsPositive) {
  Rng rng(4);
  constexpr int kN = 400'000;
  const double mean = 3.0;
  double sum = 0.0;
  int above_mean = 0;
  for (int i = 0; i < kN; ++i) {
    const double x = rng.exponential(mean);
    ASSERT_GE(x, 0.0);
    ASSERT_TRUE(std::isfinite(x));
    sum += x;
    if (x > mean) ++above_mean;
  }
  EXPECT_NEAR(sum / kN, mean, 0.03);  // sd of the mean 0.0047
  EXPECT_NEAR(static_cast<double>(above_mean) / kN, std::exp(-1.0), 0.005);
}

TEST(Rng, LognormalMedianIsExpMu) {
  Rng rng(5);
  constexpr int kN = 200'000;
  int below = 0;
  for (int i = 0; i < kN; ++i) {
    const double x = rng.lognormal(1.0, 0.5);
    ASSERT_GT(x, 0.0);
    if (x < std::exp(1.0)) ++below;
  }
  EXPECT_NEAR(static_cast<double>(below) / kN, 0.5, 0.005);
}

}  // namespace
}  // namespace a3::common
