// Link-emulator settings from JSON: every key read, unknown keys and bad values refused
// naming the key, trace paths relative to the config file, and the profile overrides
// (a degraded dwell override keeps each slice's share, a share override changes it).
#include <gtest/gtest.h>

#include <fstream>

#include "common/json_file.hpp"
#include "linkemu/link_emulator_config.hpp"
#include "tests/common/common_test_util.hpp"

namespace a3::linkemu {
namespace {

using nlohmann::json;

std::string error_of(const json& object, const std::filesystem::path& base = ".") {
  try {
    parse_link_emulator_config(object, "link.json: ", base);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(LinkEmulatorConfig, ReadsEverySetting) {
  a3::test::TempDir dir;
  {
    std::ofstream trace(dir.path() / "trace.json");
    trace << R"([{"slice": "mMTC", "lat_ms": 90, "jitter_ms": 9, "loss_pct": 2, "throughput_mbps": 2.3, "edge_load": 0.8}])";
  }
  const json doc = json::parse(R"({
    "seed": 18446744073709551615, "slice": "URLLC", "start_regime": "degraded",
    "redraw_mean_s": 1.5, "degraded_dwell_mean_s": 12, "min_dwell_s": 2, "degraded_share": 0.25,
    "handover_delay_ms": 250, "net_rate_hz": 20, "reordering": true,
    "gilbert_elliott": {"mean_burst_messages": 6, "loss_in_bad": 0.7},
    "edge_max_load": 0.9, "max_message_bytes": 1000, "max_pending_messages": 50,
    "max_pending_bytes": 5000, "max_backlog_s": 3, "publish_records": false,
    "trace": {"path": "trace.json", "period_s": 2, "loop": true}})");
  const LinkEmulatorConfig c = parse_link_emulator_config(doc, "link.json: ", dir.path());
  EXPECT_EQ(c.seed, 18446744073709551615ULL);
  EXPECT_EQ(c.initial_slice, Slice::kUrllc);
  EXPECT_EQ(c.start_regime, StartRegime::kDegraded);
  EXPECT_EQ(*c.redraw_mean_s, 1.5);
  EXPECT_EQ(*c.degraded_dwell_mean_s, 12.0);
  EXPECT_EQ(*c.min_dwell_s, 2.0);
  EXPECT_EQ(*c.degraded_share, 0.25);
  EXPECT_EQ(c.handover_delay_ms, 250.0);
  EXPECT_EQ(c.net_rate_hz, 20.0);
  EXPECT_TRUE(c.link.reordering);
  EXPECT_TRUE(c.link.gilbert_elliott.enabled);
  EXPECT_EQ(c.link.gilbert_elliott.mean_burst_messages, 6.0);
  EXPECT_EQ(c.link.gilbert_elliott.loss_in_bad, 0.7);
  EXPECT_EQ(c.edge.max_load, 0.9);
  EXPECT_EQ(c.max_message_bytes, 1000);
  EXPECT_EQ(c.max_pending_messages, 50);
  EXPECT_EQ(c.max_pending_bytes, 5000);
  EXPECT_EQ(c.max_backlog_s, 3.0);
  EXPECT_FALSE(c.publish_records);
  ASSERT_TRUE(c.trace.has_value());
  EXPECT_EQ(c.trace->points.at(0).state.slice, Slice::kMmtc);
  EXPECT_EQ(c.trace->last_hold_us, 2'000'000);
  EXPECT_TRUE(c.trace_loop);
}

TEST(LinkEmulatorConfig, RefusesUnknownKeysAndBadValuesNamingThem) {
  EXPECT_EQ(error_of(json{{"handover_ms", 5}}).rfind("link.json: /handover_ms: unknown setting (known: ", 0), 0u);
  EXPECT_EQ(error_of(json{{"slice", "6G"}}),
            "link.json: /slice: unknown slice '6G' (expected URLLC, eMBB or mMTC)");
  EXPECT_EQ(error_of(json{{"seed", -1}}), "link.json: /seed: expected a whole number >= 0");
  EXPECT_EQ(error_of(json{{"reordering", "yes"}}), "link.json: /reordering: expected true or false, got string");
  EXPECT_EQ(error_of(json{{"handover_delay_ms", -3}}), "link.json: /handover_delay_ms: -3 must be a number >= 0");
  EXPECT_EQ(error_of(json{{"degraded_share", 1.0}}), "link.json: /degraded_share: 1 must be in [0, 1)");
  EXPECT_EQ(error_of(json{{"gilbert_elliott", {{"loss_in_bad", 1.5}}}}),
            "link.json: /gilbert_elliott/loss_in_bad: 1.5 must be in (0, 1]");
  EXPECT_EQ(error_of(json{{"gilbert_elliott", {{"burst", 3}}}}).rfind("link.json: /gilbert_elliott/burst: unknown setting", 0), 0u);
  EXPECT_NE(error_of(json{{"trace", {{"path", "no-such-trace.json"}}}}).find("no-such-trace.json: cannot read"),
            std::string::npos);
  EXPECT_EQ(error_of(json::array()), "link.json: expected an object, got array");
}

TEST(LinkEmulatorConfig, ProfileOverrides) {
  const SliceProfiles& base = default_slice_profiles();
  LinkEmulatorConfig keep_shares;
  keep_shares.degraded_dwell_mean_s = 60.0;
  const SliceProfiles a = effective_profiles(base, keep_shares);
  EXPECT_EQ(a.timing.degraded_dwell_mean_s, 60.0);
  for (Slice s : kAllSlices) {
    EXPECT_EQ(a.at(s).degraded_share, base.at(s).degraded_share);
    EXPECT_DOUBLE_EQ(a.timing.normal_dwell_mean_s(a.at(s).degraded_share),
                     2.0 * base.timing.normal_dwell_mean_s(base.at(s).degraded_share));
  }
  LinkEmulatorConfig stress;
  stress.degraded_share = 0.3;
  const SliceProfiles b = effective_profiles(base, stress);
  for (Slice s : kAllSlices) EXPECT_EQ(b.at(s).degraded_share, 0.3);
}

TEST(LinkChannels, SuffixAppliesToEveryChannel) {
  const LinkChannels c = LinkChannels{}.with_suffix("_T1");
  EXPECT_EQ(c.up_tx, "A3_LINK_UP_TX_T1");
  EXPECT_EQ(c.down_rx, "A3_LINK_DOWN_RX_T1");
  EXPECT_EQ(c.net, "A3_NET_T1");
  EXPECT_EQ(c.slice_reply, "A3_SLICE_REPLY_T1");
}

}  // namespace
}  // namespace a3::linkemu
