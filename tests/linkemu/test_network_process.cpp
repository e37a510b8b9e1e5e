// The seeded network-state process: over a long run the time averages of n_t match SPEC §6
// per slice; degradations come in episodes of at least the minimum dwell, for the share of
// time the profile says, and are "hard" (SPEC §2); n_t at time t depends only on the seed
// and t; the state is piecewise constant between the announced change times.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

#include "common/rng.hpp"
#include "linkemu/regime_process.hpp"
#include "linkemu/slice_profile.hpp"
#include "linkemu/slice_state_process.hpp"
#include "linkemu/synthetic_network.hpp"
#include "tests/linkemu/linkemu_test_util.hpp"

namespace a3::linkemu {
namespace {

using test::relative_error;

constexpr int64_t kSecond = 1'000'000;

struct Samples {
  std::vector<double> lat, jitter, loss, throughput, edge;
  std::vector<bool> degraded, hard;
};

// Samples one slice's n_t once per `step_us` for `steps` steps.
Samples sample_slice(Slice slice, uint64_t seed, int64_t step_us, int steps) {
  const SliceProfiles& profiles = default_slice_profiles();
  SliceStateProcess process(profiles.at(slice), profiles.timing, common::RngStreams(seed),
                            StartRegime::kStationary, 0);
  Samples run;
  for (int i = 0; i < steps; ++i) {
    const NetworkState& s = process.state_at(static_cast<int64_t>(i) * step_us);
    EXPECT_EQ(s.slice, slice);
    run.lat.push_back(s.lat_ms);
    run.jitter.push_back(s.jitter_ms);
    run.loss.push_back(s.loss_pct);
    run.throughput.push_back(s.throughput_mbps);
    run.edge.push_back(s.edge_load);
    run.degraded.push_back(s.degraded);
    run.hard.push_back(is_hard(s));
  }
  return run;
}

// 2·10⁶ s of simulated time sampled every second: ~10⁶ independent n_t draws per slice and
// thousands of regime episodes, so the time averages are tight.
TEST(NetworkProcess, TimeAveragesMatchSpecPerSlice) {
  for (const auto& row : test::spec_rows()) {
    SCOPED_TRACE(to_string(row.slice));
    const Samples run = sample_slice(row.slice, 42, kSecond, 2'000'000);
    EXPECT_LT(relative_error(test::mean_of(run.lat), row.lat_mean_ms), 0.05) << test::mean_of(run.lat);
    EXPECT_LT(relative_error(test::quantile_of(run.lat, 0.5), row.lat_median_ms), 0.05);
    EXPECT_LT(relative_error(test::quantile_of(run.lat, 0.9), row.lat_p90_ms), 0.05);
    EXPECT_LT(relative_error(test::mean_of(run.jitter), row.jitter_mean_ms), 0.05);
    EXPECT_LT(relative_error(test::mean_of(run.loss), row.loss_mean_pct), 0.05);
    EXPECT_LT(relative_error(test::mean_of(run.throughput), row.throughput_mean_mbps), 0.05);
    EXPECT_LT(relative_error(test::mean_of(run.edge), row.edge_load_mean), 0.05);

    const double w = default_slice_profiles().at(row.slice).degraded_share;
    double degraded = 0, hard_when_degraded = 0;
    for (std::size_t i = 0; i < run.degraded.size(); ++i) {
      degraded += run.degraded[i];
      hard_when_degraded += run.degraded[i] && run.hard[i];
    }
    EXPECT_LT(relative_error(degraded / static_cast<double>(run.degraded.size()), w), 0.10)
        << "degraded share " << degraded / static_cast<double>(run.degraded.size()) << " vs " << w;
    // The degraded regime is SPEC §2's "hard" condition.
    EXPECT_GT(hard_when_degraded / degraded, 0.95);
  }
}

TEST(NetworkProcess, DegradationsComeInEpisodesOfAtLeastTheMinimumDwell) {
  const SliceProfiles& profiles = default_slice_profiles();
  common::RngStreams streams(7);
  RegimeTiming timing;
  timing.degraded_share = profiles.at(Slice::kEmbb).degraded_share;
  timing.degraded_dwell_mean_s = profiles.timing.degraded_dwell_mean_s;
  timing.normal_dwell_mean_s = profiles.timing.normal_dwell_mean_s(timing.degraded_share);
  timing.min_dwell_s = profiles.timing.min_dwell_s;
  RegimeProcess regime(streams.stream("test"), timing, StartRegime::kNormal, 0);
  std::vector<double> degraded_s, normal_s;
  int64_t t = 0;
  for (int i = 0; i < 20000; ++i) {
    (regime.degraded() ? degraded_s : normal_s).push_back((regime.episode_end_us() - regime.episode_start_us()) * 1e-6);
    t = regime.episode_end_us();
    regime.advance_to(t);
  }
  for (double d : degraded_s) ASSERT_GE(d, timing.min_dwell_s);
  for (double d : normal_s) ASSERT_GE(d, timing.min_dwell_s);
  EXPECT_LT(relative_error(test::mean_of(degraded_s), 30.0), 0.05) << test::mean_of(degraded_s);
  EXPECT_LT(relative_error(test::mean_of(normal_s), 30.0 * 0.94 / 0.06), 0.05) << test::mean_of(normal_s);
}

TEST(NetworkProcess, StartRegimeIsHonoured) {
  const SliceProfiles& profiles = default_slice_profiles();
  SliceStateProcess degraded(profiles.at(Slice::kUrllc), profiles.timing, common::RngStreams(1),
                             StartRegime::kDegraded, 0);
  SliceStateProcess normal(profiles.at(Slice::kUrllc), profiles.timing, common::RngStreams(1),
                           StartRegime::kNormal, 0);
  EXPECT_TRUE(degraded.state_at(0).degraded);
  EXPECT_FALSE(normal.state_at(0).degraded);
  // At least the minimum dwell.
  EXPECT_TRUE(degraded.state_at(4 * kSecond).degraded);
}

TEST(NetworkProcess, StateAtATimeDependsOnlyOnSeedAndTime) {
  const SliceProfiles& profiles = default_slice_profiles();
  SyntheticNetwork dense(profiles, common::RngStreams(99), StartRegime::kStationary, 0);
  SyntheticNetwork sparse(profiles, common::RngStreams(99), StartRegime::kStationary, 0);
  SyntheticNetwork other_seed(profiles, common::RngStreams(100), StartRegime::kStationary, 0);
  std::map<int64_t, NetworkState> dense_states;
  for (int64_t t = 0; t <= 3600 * kSecond; t += kSecond / 10) {
    dense_states[t] = dense.state_at(Slice::kMmtc, t);
    dense.state_at(Slice::kUrllc, t);  // asking about other slices changes nothing
  }
  int differences_with_other_seed = 0;
  for (int64_t t = 0; t <= 3600 * kSecond; t += 60 * kSecond) {
    ASSERT_EQ(sparse.state_at(Slice::kMmtc, t), dense_states.at(t)) << "t = " << t;
    differences_with_other_seed += !(other_seed.state_at(Slice::kMmtc, t) == dense_states.at(t));
  }
  EXPECT_GT(differences_with_other_seed, 55);
}

TEST(NetworkProcess, StateIsConstantUntilTheAnnouncedChange) {
  const SliceProfiles& profiles = default_slice_profiles();
  SliceStateProcess process(profiles.at(Slice::kEmbb), profiles.timing, common::RngStreams(5),
                            StartRegime::kStationary, 0);
  int changes = 0;
  int64_t t = 0;
  while (t < 600 * kSecond) {
    const NetworkState before = process.state_at(t);
    const int64_t change = process.next_change_us();
    ASSERT_GT(change, t);
    // Just before the change: same state; at it: a new draw.
    EXPECT_EQ(process.state_at(change - 1), before);
    EXPECT_NE(process.state_at(change), before);
    t = change;
    ++changes;
  }
  // Mean redraw interval 2 s: about 300 changes in 600 s.
  EXPECT_GT(changes, 200);
  EXPECT_LT(changes, 420);
}

TEST(NetworkProcess, SharedOverrideMakesEverySliceDegradedMoreOften) {
  SliceProfiles stressed = default_slice_profiles();
  for (SliceProfile& p : stressed.slices) p.degraded_share = 0.5;
  SliceStateProcess process(stressed.at(Slice::kUrllc), stressed.timing, common::RngStreams(3),
                            StartRegime::kStationary, 0);
  int degraded = 0;
  const int steps = 200000;
  for (int i = 0; i < steps; ++i) degraded += process.state_at(static_cast<int64_t>(i) * kSecond).degraded;
  EXPECT_NEAR(static_cast<double>(degraded) / steps, 0.5, 0.05);
}


// A scenario's scripted degradation: inside the window every draw is from the degraded regime
// (hard), the state changes exactly at the window's edges, and outside it the normal-regime
// start is kept.
TEST(NetworkProcess, ForcedWindowsAreDegradedExactlyWhileTheyLast) {
  const SliceProfiles& profiles = default_slice_profiles();
  const int64_t start = 60 * kSecond, end = 90 * kSecond;
  SliceStateProcess process(profiles.at(Slice::kUrllc), profiles.timing, common::RngStreams(8), StartRegime::kNormal,
                            0, {{start, end}});
  SliceStateProcess unforced(profiles.at(Slice::kUrllc), profiles.timing, common::RngStreams(8), StartRegime::kNormal,
                             0);
  EXPECT_FALSE(process.state_at(0).degraded);
  int64_t t = 0;
  bool saw_change_at_start = false, saw_change_at_end = false;
  while (t < 150 * kSecond) {
    const NetworkState s = process.state_at(t);
    if (t >= start && t < end) {
      ASSERT_TRUE(s.degraded) << "t = " << t;
      ASSERT_TRUE(is_hard(s)) << "t = " << t;
    }
    const int64_t change = process.next_change_us();
    ASSERT_GT(change, t);
    saw_change_at_start |= change == start;
    saw_change_at_end |= change == end;
    t = std::min(change, t + kSecond);
  }
  EXPECT_TRUE(saw_change_at_start) << "the state is redrawn when the window opens";
  EXPECT_TRUE(saw_change_at_end) << "and when it closes";
  // Without the window the same seed is (almost always) normal at those times.
  int unforced_degraded = 0;
  for (int64_t u = start; u < end; u += kSecond) unforced_degraded += unforced.state_at(u).degraded;
  EXPECT_EQ(unforced_degraded, 0) << "seed 8 has no degradation of its own there";
}

}  // namespace
}  // namespace a3::linkemu
