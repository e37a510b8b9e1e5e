// WallClock (monotonic, scaled by the real-time factor, mono_ns_at its inverse, bad factors
// rejected) and VirtualClock (moves only forward).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "common/clock.hpp"

namespace a3::common {
namespace {

using std::chrono::milliseconds;

TEST(WallClock, StartsNearZeroAndNeverGoesBackwards) {
  const WallClock clock;
  const int64_t first = clock.now_us();
  EXPECT_GE(first, 0);
  EXPECT_LT(first, 1'000'000) << "a clock that starts now reads less than 1 s at once";
  int64_t previous = first;
  for (int i = 0; i < 100000; ++i) {
    const int64_t t = clock.now_us();
    ASSERT_GE(t, previous) << "went back at read " << i;
    previous = t;
  }
  EXPECT_NEAR(clock.now_s(), static_cast<double>(clock.now_us()) * 1e-6, 0.01);
}

TEST(WallClock, AdvancesWithWallTime) {
  const WallClock clock;
  const int64_t before = clock.now_us();
  std::this_thread::sleep_for(milliseconds(30));
  const int64_t elapsed = clock.now_us() - before;
  EXPECT_GE(elapsed, 30'000) << "sleep_for never returns early";
  EXPECT_LT(elapsed, 5'000'000) << "generous: a loaded machine, but not a stopped clock";
}

// Brackets the simulated interval with monotonic readings taken outside and inside it:
// factor * inner <= simulated <= factor * outer, independently of machine load.
void expect_scaled(double factor, milliseconds sleep) {
  const WallClock clock(factor);
  EXPECT_EQ(clock.real_time_factor(), factor);
  const int64_t outer0 = WallClock::monotonic_now_ns();
  const int64_t sim0 = clock.now_us();
  const int64_t inner0 = WallClock::monotonic_now_ns();
  std::this_thread::sleep_for(sleep);
  const int64_t inner1 = WallClock::monotonic_now_ns();
  const int64_t sim1 = clock.now_us();
  const int64_t outer1 = WallClock::monotonic_now_ns();

  const double sim_us = static_cast<double>(sim1 - sim0);
  const double inner_us = static_cast<double>(inner1 - inner0) * 1e-3;
  const double outer_us = static_cast<double>(outer1 - outer0) * 1e-3;
  EXPECT_GE(sim_us, factor * inner_us - 2.0) << "factor " << factor;
  EXPECT_LE(sim_us, factor * outer_us + 2.0) << "factor " << factor;
  // And the plain behaviour: at least factor x the requested sleep passed in simulation.
  EXPECT_GE(sim_us, factor * 1e3 * static_cast<double>(sleep.count()) - 2.0);
}

TEST(WallClock, RealTimeFactorTenRunsTenTimesFaster) { expect_scaled(10.0, milliseconds(40)); }
TEST(WallClock, RealTimeFactorHalfRunsAtHalfSpeed) { expect_scaled(0.5, milliseconds(40)); }
TEST(WallClock, RealTimeFactorOneIsWallTime) { expect_scaled(1.0, milliseconds(20)); }

TEST(WallClock, ClocksWithTheSameEpochAgreeAndScale) {
  const int64_t epoch = WallClock::monotonic_now_ns() - 2'000'000'000;  // 2 s ago
  const WallClock slow(1.0, epoch);
  const WallClock fast(10.0, epoch);
  EXPECT_EQ(fast.epoch_mono_ns(), epoch);
  const int64_t slow_us = slow.now_us();
  const int64_t fast_us = fast.now_us();
  EXPECT_GE(slow_us, 2'000'000);
  // Read a few microseconds apart; 10x of ~2 s is ~20 s.
  EXPECT_NEAR(static_cast<double>(fast_us), 10.0 * static_cast<double>(slow_us), 10.0 * 50'000.0);
  const WallClock same(1.0, epoch);
  EXPECT_NEAR(static_cast<double>(same.now_us()), static_cast<double>(slow.now_us()), 50'000.0);
}

TEST(WallClock, MonoNsAtIsTheInverseOfNowUs) {
  for (const double factor : {1.0, 10.0, 0.5, 3.0}) {
    const WallClock clock(factor, WallClock::monotonic_now_ns() - 1'000'000'000);
    EXPECT_EQ(clock.mono_ns_at(0), clock.epoch_mono_ns()) << "factor " << factor;
    for (int i = 0; i < 1000; ++i) {
      const int64_t m0 = WallClock::monotonic_now_ns();
      const int64_t t = clock.now_us();
      const int64_t m1 = WallClock::monotonic_now_ns();
      // Simulated time t had been reached by the time it was read...
      ASSERT_LE(clock.mono_ns_at(t), m1) << "factor " << factor << ", t " << t;
      // ...and t + 1 had not yet been reached before it was read.
      ASSERT_GT(clock.mono_ns_at(t + 1), m0) << "factor " << factor << ", t " << t;
    }
    // One simulated second is 1/factor wall seconds.
    const int64_t wall_ns = clock.mono_ns_at(5'000'000) - clock.mono_ns_at(4'000'000);
    EXPECT_NEAR(static_cast<double>(wall_ns), 1e9 / factor, 2.0) << "factor " << factor;
  }
}

TEST(WallClock, MonoNsAtIsMonotonicInSimTime) {
  const WallClock clock(3.0, 0);
  int64_t previous = clock.mono_ns_at(0);
  for (int64_t t = 1; t < 100000; t += 7) {
    const int64_t m = clock.mono_ns_at(t);
    ASSERT_GT(m, previous) << "t " << t;
    previous = m;
  }
}

TEST(WallClock, RejectsBadRealTimeFactorNamingTheValue) {
  for (const double bad : {0.0, -1.0, -0.0, std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()}) {
    try {
      const WallClock clock(bad);
      ADD_FAILURE() << "accepted real-time factor " << bad;
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("real-time factor"), std::string::npos) << what;
      EXPECT_NE(what.find(std::to_string(bad)), std::string::npos) << what;
    }
  }
  EXPECT_NO_THROW(WallClock(1e-3));
  EXPECT_NO_THROW(WallClock(1000.0));
}

TEST(VirtualClock, StartsWhereToldAndMovesForward) {
  VirtualClock clock(1500);
  EXPECT_EQ(clock.now_us(), 1500);
  clock.advance_to(1500);  // staying put is allowed
  EXPECT_EQ(clock.now_us(), 1500);
  clock.advance_to(2'000'000);
  EXPECT_EQ(clock.now_us(), 2'000'000);
  EXPECT_DOUBLE_EQ(clock.now_s(), 2.0);
}

TEST(VirtualClock, NeverGoesBackwards) {
  VirtualClock clock(0);
  clock.advance_to(1000);
  try {
    clock.advance_to(999);
    ADD_FAILURE() << "went back from 1000 to 999";
  } catch (const std::logic_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("1000"), std::string::npos) << what;
    EXPECT_NE(what.find("999"), std::string::npos) << what;
  }
  EXPECT_EQ(clock.now_us(), 1000) << "a refused move leaves the clock where it was";
  EXPECT_THROW(clock.advance_to(-1), std::logic_error);
}

}  // namespace
}  // namespace a3::common
