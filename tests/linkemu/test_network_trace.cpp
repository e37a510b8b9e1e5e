// Network traces: the three accepted layouts (timed points, {"trace"} objects, α³-Bench
// episodes — a public episode is used as is), errors that name the point and the field,
// and the replay's piecewise-constant timing (hold, loop).
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <string>

#include "common/json_file.hpp"
#include "linkemu/network_trace.hpp"
#include "linkemu/trace_replay.hpp"
#include "tests/linkemu/linkemu_test_util.hpp"
#include "tests/test_support.hpp"

namespace a3::linkemu {
namespace {

using nlohmann::json;
constexpr int64_t kSecond = 1'000'000;

json point(const char* slice, double lat_ms, double loss_pct = 0.1) {
  return {{"slice", slice}, {"lat_ms", lat_ms}, {"jitter_ms", 1.5}, {"loss_pct", loss_pct},
          {"throughput_mbps", 90}, {"edge_load", 0.4}};
}

TEST(NetworkTrace, TimedPointsKeepTheirTimesAndValues) {
  json doc = json::array();
  doc.push_back(point("URLLC", 8.5));
  doc.push_back(point("eMBB", 55.0));
  doc.push_back(point("mMTC", 120.0, 3.0));
  doc[0]["t_s"] = 0.0;
  doc[1]["t_s"] = 2.5;
  doc[2]["t_s"] = 7.25;
  doc[1]["degraded"] = false;  // explicit flag wins over the hard test
  const NetworkTrace trace = parse_network_trace(doc, "t.json: ");
  ASSERT_EQ(trace.points.size(), 3u);
  EXPECT_EQ(trace.points[1].t_us, 2'500'000);
  EXPECT_EQ(trace.points[2].t_us, 7'250'000);
  EXPECT_EQ(trace.points[1].state.slice, Slice::kEmbb);
  EXPECT_DOUBLE_EQ(trace.points[1].state.lat_ms, 55.0);
  EXPECT_FALSE(trace.points[1].state.degraded);
  EXPECT_TRUE(trace.points[2].state.degraded) << "lat 120 ms, loss 3 %: hard by SPEC §2";
  EXPECT_FALSE(trace.points[0].state.degraded);
  EXPECT_EQ(trace.last_hold_us, static_cast<int64_t>(kDefaultTracePeriodS * kSecond));
}

TEST(NetworkTrace, UntimedPointsAreSpacedByThePeriod) {
  json doc = {{"period_s", 3.0}, {"trace", json::array({point("URLLC", 5), point("URLLC", 6), point("eMBB", 20)})}};
  const NetworkTrace trace = parse_network_trace(doc, "t.json: ", 10.0);
  ASSERT_EQ(trace.points.size(), 3u);
  EXPECT_EQ(trace.points[2].t_us, 6 * kSecond) << "the document's period_s wins";
  EXPECT_EQ(trace.duration_us(), 9 * kSecond);
}

TEST(NetworkTrace, PublicEpisodeIsUsableDirectly) {
  A3_REQUIRE_SHARED(file, "alphabench/eval_runs/openai/chatgpt-4o-latest/uav/sc-0000-ep-00.json");
  const NetworkTrace trace = load_network_trace(file, 4.0);
  const json episode = common::load_json_file(file);
  const json& dialogue = episode.at("dialogue");
  ASSERT_EQ(trace.points.size(), dialogue.size());
  for (std::size_t i = 0; i < dialogue.size(); ++i) {
    const json& net = dialogue[i].at("net");
    SCOPED_TRACE("turn " + std::to_string(i + 1));
    EXPECT_EQ(trace.points[i].t_us, static_cast<int64_t>(i) * 4 * kSecond);
    EXPECT_EQ(to_string(trace.points[i].state.slice), net.at("slice").get<std::string>());
    EXPECT_DOUBLE_EQ(trace.points[i].state.lat_ms, net.at("lat_ms").get<double>());
    EXPECT_DOUBLE_EQ(trace.points[i].state.jitter_ms, net.at("jitter_ms").get<double>());
    EXPECT_DOUBLE_EQ(trace.points[i].state.loss_pct, net.at("loss_pct").get<double>());
    EXPECT_DOUBLE_EQ(trace.points[i].state.throughput_mbps, net.at("throughput_mbps").get<double>());
    EXPECT_DOUBLE_EQ(trace.points[i].state.edge_load, net.at("edge_load").get<double>());
    EXPECT_EQ(trace.points[i].state.degraded, is_hard(trace.points[i].state));
  }
}

TEST(NetworkTrace, EveryPublicEpisodeWithTurnsLoads) {
  A3_REQUIRE_SHARED(root, "alphabench/eval_runs");
  int loaded = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".json") continue;
    const json doc = common::load_json_file(entry.path());
    if (doc.at("dialogue").empty()) continue;  // failure stubs have no turns
    EXPECT_NO_THROW(load_network_trace(entry.path())) << entry.path();
    ++loaded;
  }
  EXPECT_GE(loaded, 150);
}

std::string error_of(const json& doc) {
  try {
    parse_network_trace(doc, "t.json: ");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(NetworkTrace, BadTracesAreRefusedNamingPointAndField) {
  json bad_slice = json::array({point("URLLC", 5), point("6G", 5)});
  EXPECT_EQ(error_of(bad_slice),
            "t.json: /1/slice: unknown slice '6G' (expected URLLC, eMBB or mMTC)");
  json bad_loss = json::array({point("URLLC", 5, 120.0)});
  EXPECT_EQ(error_of(bad_loss), "t.json: /0/loss_pct: 120 is outside [0, 100]");
  json zero_throughput = json::array({point("URLLC", 5)});
  zero_throughput[0]["throughput_mbps"] = 0;
  EXPECT_EQ(error_of(zero_throughput), "t.json: /0/throughput_mbps: 0 is outside (0, inf]");
  json missing = json::array({point("URLLC", 5)});
  missing[0].erase("edge_load");
  EXPECT_EQ(error_of(missing), "t.json: /0/edge_load: missing");
  json backwards = json::array({point("URLLC", 5), point("URLLC", 6)});
  backwards[0]["t_s"] = 2.0;
  backwards[1]["t_s"] = 1.0;
  EXPECT_NE(error_of(backwards).find("t.json: /1/t_s: times must increase"), std::string::npos);
  json mixed = json::array({point("URLLC", 5), point("URLLC", 6)});
  mixed[0]["t_s"] = 0.0;
  EXPECT_EQ(error_of(mixed), "t.json: /1: \"t_s\" must be on every point or on none");
  EXPECT_EQ(error_of(json::array()), "t.json: the trace has no points");
  EXPECT_EQ(error_of(json{{"trace", json::array()}}), "t.json: /trace: the trace has no points");
  EXPECT_EQ(error_of(json{{"dialogue", json::array({json{{"turn", 1}}})}}),
            "t.json: /dialogue/0/net: missing");
  EXPECT_NE(error_of(json("text")).find("expected a list of n_t points"), std::string::npos);
}

TEST(TraceReplay, HoldsEachPointUntilTheNextAndTheLastForGood) {
  NetworkTrace trace;
  trace.points = {{2 * kSecond, test::make_state(Slice::kUrllc, 5, 1, 0.1, 90, 0.3)},
                  {5 * kSecond, test::make_state(Slice::kMmtc, 80, 9, 2, 2, 0.8)}};
  trace.last_hold_us = kSecond;
  const int64_t start = 100 * kSecond;
  TraceReplay replay(trace, start, false);
  EXPECT_EQ(replay.state_at(Slice::kEmbb, start).slice, Slice::kUrllc) << "the first point holds before its time";
  EXPECT_EQ(replay.next_change_us(Slice::kEmbb), start + 5 * kSecond);
  EXPECT_EQ(replay.state_at(Slice::kEmbb, start + 5 * kSecond - 1).slice, Slice::kUrllc);
  EXPECT_EQ(replay.state_at(Slice::kEmbb, start + 5 * kSecond), trace.points[1].state);
  EXPECT_EQ(replay.next_change_us(Slice::kEmbb), std::numeric_limits<int64_t>::max());
  EXPECT_EQ(replay.state_at(Slice::kEmbb, start + 3600 * kSecond), trace.points[1].state);
  EXPECT_TRUE(replay.dictates_slice());
}

TEST(TraceReplay, LoopsAfterTheLastPointsHold) {
  NetworkTrace trace;
  trace.points = {{0, test::make_state(Slice::kUrllc, 5, 1, 0.1, 90, 0.3)},
                  {kSecond, test::make_state(Slice::kEmbb, 20, 3, 0.5, 500, 0.5)}};
  trace.last_hold_us = 2 * kSecond;  // duration 3 s
  TraceReplay replay(trace, 0, true);
  EXPECT_EQ(replay.state_at(Slice::kEmbb, 2 * kSecond).slice, Slice::kEmbb);
  EXPECT_EQ(replay.next_change_us(Slice::kEmbb), 3 * kSecond);
  EXPECT_EQ(replay.state_at(Slice::kEmbb, 3 * kSecond).slice, Slice::kUrllc);
  EXPECT_EQ(replay.state_at(Slice::kEmbb, 4 * kSecond).slice, Slice::kEmbb);
  EXPECT_EQ(replay.state_at(Slice::kEmbb, 30 * kSecond + 500000).slice, Slice::kUrllc);
}

}  // namespace
}  // namespace a3::linkemu
