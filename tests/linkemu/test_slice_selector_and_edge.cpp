// Slice switching with a handover delay (pending, superseded, cancelled, immediate) and
// the edge-compute delay model (work / (1 - load), load capped).
#include <gtest/gtest.h>

#include <limits>

#include "linkemu/edge_compute.hpp"
#include "linkemu/slice_selector.hpp"

namespace a3::linkemu {
namespace {

TEST(SliceSelector, SwitchTakesEffectAfterTheHandoverDelay) {
  SliceSelector selector(Slice::kEmbb, 100'000);
  const SwitchResult r = selector.request(Slice::kUrllc, 1'000'000);
  EXPECT_TRUE(r.accepted);
  EXPECT_EQ(r.from, Slice::kEmbb);
  EXPECT_EQ(r.effective_us, 1'100'000);
  EXPECT_EQ(selector.pending(), Slice::kUrllc);
  EXPECT_EQ(selector.active_at(1'099'999), Slice::kEmbb);
  EXPECT_EQ(selector.active_at(1'100'000), Slice::kUrllc);
  EXPECT_FALSE(selector.pending().has_value());
  EXPECT_EQ(selector.pending_effective_us(), std::numeric_limits<int64_t>::max());
  EXPECT_EQ(selector.switches_done(), 1u);
}

TEST(SliceSelector, LaterRequestsReplaceOrCancelAPendingOne) {
  SliceSelector selector(Slice::kEmbb, 100'000);
  selector.request(Slice::kUrllc, 0);
  const SwitchResult same = selector.request(Slice::kUrllc, 50'000);
  EXPECT_EQ(same.note, "already pending");
  EXPECT_EQ(same.effective_us, 100'000) << "a repeated request does not restart the handover";
  const SwitchResult other = selector.request(Slice::kMmtc, 60'000);
  EXPECT_EQ(other.note, "replaces the pending switch to URLLC");
  EXPECT_EQ(other.effective_us, 160'000);
  const SwitchResult back = selector.request(Slice::kEmbb, 70'000);
  EXPECT_EQ(back.note, "replaces the pending switch to mMTC");
  EXPECT_FALSE(selector.pending().has_value());
  EXPECT_EQ(selector.active_at(1'000'000), Slice::kEmbb);
  EXPECT_EQ(selector.switches_done(), 0u);
}

TEST(SliceSelector, ZeroDelaySwitchesAtOnce) {
  SliceSelector selector(Slice::kEmbb, 0);
  EXPECT_EQ(selector.request(Slice::kMmtc, 5).effective_us, 5);
  EXPECT_EQ(selector.active_at(5), Slice::kMmtc);
  EXPECT_THROW(SliceSelector(Slice::kEmbb, -1), std::invalid_argument);
}

TEST(EdgeCompute, ProcessorSharingSlowdown) {
  const EdgeComputeModel edge;
  EXPECT_DOUBLE_EQ(edge.delay_ms(100.0, 0.0), 100.0);
  EXPECT_DOUBLE_EQ(edge.delay_ms(100.0, 0.5), 200.0);
  EXPECT_NEAR(edge.delay_ms(100.0, 0.8), 500.0, 1e-9);
  EXPECT_NEAR(edge.delay_ms(100.0, 1.0), 2000.0, 1e-9) << "capped at 0.95";
  EXPECT_DOUBLE_EQ(edge.delay_ms(0.0, 0.9), 0.0);
  EXPECT_THROW(edge.delay_ms(-1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(edge.delay_ms(std::numeric_limits<double>::quiet_NaN(), 0.5), std::invalid_argument);
  EdgeComputeModel strict;
  strict.max_load = 0.5;
  EXPECT_DOUBLE_EQ(strict.delay_ms(100.0, 0.9), 200.0);
}

}  // namespace
}  // namespace a3::linkemu
