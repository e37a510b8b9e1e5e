// The link emulator node on the virtual-time runtime: relaying both ways with the timing
// the model gives, large payloads that take seconds and delay what follows but not the
// other direction, FIFO, the same schedule for the same seed, trace replay reproducing the
// trace's n_t at the right times (a public episode included), slice switching with the
// handover delay (in-flight messages keep their slice), edge-compute answers, and bad
// input dropped with a counted, recorded reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "a3lcm/edge_compute_request_t.hpp"
#include "a3lcm/slice_switch_request_t.hpp"
#include "common/runtime.hpp"
#include "linkemu/link_emulator_node.hpp"
#include "tests/linkemu/linkemu_test_util.hpp"
#include "tests/test_support.hpp"

namespace a3::linkemu {
namespace {

using test::ClientNode;
using test::constant_trace;
using test::make_message;
using test::make_state;
constexpr int64_t kSecond = 1'000'000;
constexpr int64_t kMs = 1'000;

LinkEmulatorConfig config_with_trace(const NetworkState& state) {
  LinkEmulatorConfig c;
  c.trace = constant_trace(state);
  return c;
}

// Runs a node and a client together in virtual time until end_us.
void run(LinkEmulatorNode& node, ClientNode& client, int64_t end_us) {
  common::VirtualRuntime runtime;
  runtime.add(node);
  runtime.add(client);
  runtime.run_until(end_us);
}

TEST(LinkEmulatorNode, RelaysBothDirectionsWithTheModelsTiming) {
  LinkEmulatorNode node(config_with_trace(make_state(Slice::kEmbb, 20, 0, 0, 100, 0.5)));
  ClientNode client;
  client.send_at(1 * kSecond, true, make_message(1, "agent", 1000));
  client.send_at(1500 * kMs, false, make_message(2, "tool_server", 500, 10000));
  run(node, client, 5 * kSecond);

  ASSERT_EQ(client.up_rx.size(), 1u);
  ASSERT_EQ(client.down_rx.size(), 1u);
  const auto& up = client.up_rx[0];
  EXPECT_EQ(up.recv_us, 1 * kSecond + 80 + 20 * kMs) << "1000 B at 100 Mbps = 80 us, then 20 ms";
  EXPECT_EQ(up.message.utime_us, up.recv_us);
  EXPECT_EQ(up.message.sent_utime_us, 1 * kSecond);
  EXPECT_EQ(up.message.slice, "eMBB");
  EXPECT_EQ(up.message.payload, make_message(1, "agent", 1000).payload);
  EXPECT_EQ(client.down_rx[0].recv_us, 1500 * kMs + 800 + 20 * kMs) << "charged 10000 B, not the 500 carried";

  ASSERT_EQ(client.records.size(), 2u);
  const auto& r = client.records[0];
  EXPECT_EQ(r.direction, "up");
  EXPECT_EQ(r.message_id, 1);
  EXPECT_EQ(r.sender, "agent");
  EXPECT_EQ(r.outcome, int8_t{a3lcm::link_record_t::DELIVERED});
  EXPECT_EQ(r.delivery_utime_us, up.recv_us);
  EXPECT_EQ(r.size_bytes, 1000);
  EXPECT_DOUBLE_EQ(r.queue_ms, 0.0);
  EXPECT_DOUBLE_EQ(r.serialization_ms, 0.08);
  EXPECT_DOUBLE_EQ(r.latency_ms, 20.0);
  EXPECT_EQ(r.slice, "eMBB");
  EXPECT_DOUBLE_EQ(r.net_lat_ms, 20.0);
  EXPECT_DOUBLE_EQ(r.net_throughput_mbps, 100.0);
  EXPECT_EQ(client.records[1].size_bytes, 10000);

  EXPECT_EQ(node.stats().up.received, 1u);
  EXPECT_EQ(node.stats().up.delivered, 1u);
  EXPECT_EQ(node.stats().down.delivered, 1u);
  EXPECT_EQ(node.stats().up.pending, 0u);
}

// In lockstep a datagram can be heard one quantum before the grant of the time it was sent at:
// it enters the link at its send time (up to 100 ms ahead), never before it is heard.
TEST(LinkEmulatorNode, AMessageEntersTheLinkAtItsSendTimeIfThatIsLaterThanWhenItIsHeard) {
  LinkEmulatorNode node(config_with_trace(make_state(Slice::kEmbb, 20, 0, 0, 100, 0.5)));
  ClientNode client;
  const std::vector<int64_t> sent_us = {1 * kSecond + 4 * kMs, 2 * kSecond + 60 * kSecond, 3 * kSecond - 500 * kMs};
  for (std::size_t i = 0; i < sent_us.size(); ++i) {
    client.at(static_cast<int64_t>(i + 1) * kSecond, [&sent_us, i](common::Executor& executor, common::Bus& bus) {
      a3lcm::link_message_t m = make_message(static_cast<int64_t>(i + 1), "agent", 1000);
      m.utime_us = executor.clock().now_us();
      m.sent_utime_us = sent_us[i];
      bus.publish(LinkChannels{}.up_tx, m);
    });
  }
  run(node, client, 5 * kSecond);

  ASSERT_EQ(client.up_rx.size(), 3u);
  const int64_t transit_us = 80 + 20 * kMs;  // 1000 B at 100 Mbps, then 20 ms
  EXPECT_EQ(client.up_rx[0].recv_us, 1 * kSecond + 4 * kMs + transit_us) << "sent 4 ms after it was heard";
  EXPECT_EQ(client.up_rx[1].recv_us, 2 * kSecond + 100 * kMs + transit_us) << "a send time 60 s ahead: 100 ms at most";
  EXPECT_EQ(client.up_rx[2].recv_us, 3 * kSecond + transit_us) << "sent before it was heard: enters when heard";
  ASSERT_EQ(client.records.size(), 3u);
  EXPECT_EQ(client.records[0].utime_us, 1 * kSecond) << "the record says when it was heard";
  EXPECT_EQ(client.records[0].sent_utime_us, 1 * kSecond + 4 * kMs);
}

TEST(LinkEmulatorNode, FiveMegabyteImageOnMmtcTakesSecondsAndDelaysWhatFollowsOnly) {
  LinkEmulatorNode node(config_with_trace(make_state(Slice::kMmtc, 50, 0, 0, 2.3, 0.7)));
  ClientNode client;
  client.send_at(1 * kSecond, false, make_message(1, "tool_server", 5'000'000));  // the image, down
  client.send_at(2 * kSecond, false, make_message(2, "tool_server", 200));
  client.send_at(2 * kSecond, true, make_message(3, "agent", 200));
  run(node, client, 60 * kSecond);

  ASSERT_EQ(client.down_rx.size(), 2u);
  ASSERT_EQ(client.up_rx.size(), 1u);
  const int64_t image_arrival = client.down_rx[0].recv_us;
  EXPECT_EQ(client.down_rx[0].message.message_id, 1);
  EXPECT_EQ(client.down_rx[0].message.payload, make_message(1, "tool_server", 5'000'000).payload);
  EXPECT_GE(image_arrival - 1 * kSecond, static_cast<int64_t>(5e6 * 8 / 2.3)) << "no earlier than its serialization time";
  EXPECT_EQ(client.down_rx[1].message.message_id, 2);
  EXPECT_GT(client.down_rx[1].recv_us, image_arrival) << "queued behind the image";
  // The other direction does not wait for the image.
  EXPECT_EQ(client.up_rx[0].recv_us, 2 * kSecond + serialization_us(200, 2.3) + 50 * kMs);
  EXPECT_GT(client.records[1].queue_ms, 16000.0);
}

std::vector<int64_t> up_ids(const ClientNode& client) {
  std::vector<int64_t> ids;
  for (const auto& r : client.up_rx) ids.push_back(r.message.message_id);
  return ids;
}

TEST(LinkEmulatorNode, FifoPerDirectionUnlessReorderingIsOn) {
  for (bool reordering : {false, true}) {
    SCOPED_TRACE(reordering ? "reordering" : "FIFO");
    LinkEmulatorConfig config = config_with_trace(make_state(Slice::kMmtc, 80, 30, 0, 50, 0.7));
    config.link.reordering = reordering;
    LinkEmulatorNode node(config);
    ClientNode client;
    for (int i = 0; i < 2000; ++i) client.send_at(kSecond + i * 500, true, make_message(i, "agent", 100));
    run(node, client, 10 * kSecond);
    ASSERT_EQ(client.up_rx.size(), 2000u);
    const std::vector<int64_t> ids = up_ids(client);
    const bool in_order = std::is_sorted(ids.begin(), ids.end());
    EXPECT_EQ(in_order, !reordering);
    for (std::size_t i = 1; i < client.up_rx.size(); ++i) {
      ASSERT_GE(client.up_rx[i].recv_us, client.up_rx[i - 1].recv_us);
    }
  }
}

struct Schedule {
  std::vector<std::tuple<std::string, int64_t, int, int64_t, std::string>> records;
  std::vector<std::tuple<int64_t, std::string, double, bool>> net;
  bool operator==(const Schedule&) const = default;
};

// A busy run on the seeded process: both directions, slice switches, an edge request.
Schedule busy_run(uint64_t seed) {
  LinkEmulatorConfig config;
  config.seed = seed;
  config.net_rate_hz = 1.0;
  LinkEmulatorNode node(config);
  ClientNode client;
  for (int i = 0; i < 1500; ++i) {
    client.send_at(i * 200 * kMs, i % 2 == 0, make_message(i, i % 2 ? "tool_server" : "agent", 100 + (i * 37) % 5000));
  }
  const char* slices[] = {"URLLC", "mMTC", "eMBB"};
  for (int k = 0; k < 6; ++k) {
    client.at((20 + 40 * k) * kSecond, [k, &slices](common::Executor& ex, common::Bus& bus) {
      a3lcm::slice_switch_request_t r{};
      r.utime_us = ex.clock().now_us();
      r.request_id = k;
      r.requester = "test";
      r.slice = slices[k % 3];
      bus.publish(common::channels::kSliceRequest.of(0), r);
    });
  }
  run(node, client, 320 * kSecond);
  Schedule s;
  for (const auto& r : client.records) {
    s.records.emplace_back(r.direction, r.message_id, r.outcome, r.delivery_utime_us, r.slice);
  }
  for (const auto& n : client.net) s.net.emplace_back(n.utime_us, n.slice, n.lat_ms, n.degraded);
  EXPECT_EQ(client.records.size(), 1500u);
  return s;
}

TEST(LinkEmulatorNode, SameSeedGivesTheSameDeliveryScheduleInVirtualTime) {
  const Schedule a = busy_run(77);
  const Schedule b = busy_run(77);
  const Schedule c = busy_run(78);
  EXPECT_TRUE(a == b);
  EXPECT_FALSE(a == c);
  std::map<std::string, int> slices;
  for (const auto& r : a.records) ++slices[std::get<4>(r)];
  EXPECT_EQ(slices.size(), 3u) << "the switches moved traffic over every slice";
}

TEST(LinkEmulatorNode, TraceReplayPublishesTheTracesNtAtItsTimes) {
  NetworkTrace trace;
  trace.points = {{0, make_state(Slice::kUrllc, 6, 1, 0.05, 90, 0.3)},
                  {3 * kSecond, make_state(Slice::kEmbb, 45, 8, 1.5, 300, 0.6)},
                  {4500 * kMs, make_state(Slice::kMmtc, 130, 20, 3, 1.5, 0.9)},
                  {10 * kSecond, make_state(Slice::kUrllc, 8, 1, 0.1, 95, 0.35)}};
  trace.last_hold_us = kSecond;
  LinkEmulatorConfig config;
  config.trace = trace;
  config.net_rate_hz = 0.0;  // only on change: one message per point
  LinkEmulatorNode node(config);
  ClientNode client;
  client.send_at(3500 * kMs, true, make_message(1, "agent", 100));
  client.send_at(11 * kSecond, false, make_message(2, "tool_server", 100));
  client.at(5 * kSecond, [](common::Executor& ex, common::Bus& bus) {
    a3lcm::slice_switch_request_t r{};
    r.utime_us = ex.clock().now_us();
    r.slice = "URLLC";
    bus.publish(common::channels::kSliceRequest.of(0), r);
  });
  run(node, client, 20 * kSecond);

  // One A3_NET per trace point at its time, plus one after the refused switch request.
  std::vector<a3lcm::network_state_t> at_points;
  for (const auto& n : client.net) {
    if (n.utime_us != 5 * kSecond) at_points.push_back(n);
  }
  ASSERT_EQ(at_points.size(), trace.points.size());
  for (std::size_t i = 0; i < trace.points.size(); ++i) {
    SCOPED_TRACE("point " + std::to_string(i));
    const NetworkState& want = trace.points[i].state;
    EXPECT_EQ(at_points[i].utime_us, trace.points[i].t_us);
    EXPECT_EQ(at_points[i].slice, to_string(want.slice));
    EXPECT_EQ(at_points[i].lat_ms, want.lat_ms);
    EXPECT_EQ(at_points[i].jitter_ms, want.jitter_ms);
    EXPECT_EQ(at_points[i].loss_pct, want.loss_pct);
    EXPECT_EQ(at_points[i].throughput_mbps, want.throughput_mbps);
    EXPECT_EQ(at_points[i].edge_load, want.edge_load);
    EXPECT_EQ(at_points[i].degraded, want.degraded);
  }
  ASSERT_EQ(client.records.size(), 2u);
  EXPECT_EQ(client.records[0].slice, "eMBB");
  EXPECT_EQ(client.records[0].net_lat_ms, 45.0);
  EXPECT_EQ(client.records[1].slice, "URLLC");
  EXPECT_EQ(client.records[1].net_lat_ms, 8.0);
  ASSERT_EQ(client.slice_replies.size(), 1u);
  EXPECT_FALSE(client.slice_replies[0].accepted);
  EXPECT_NE(client.slice_replies[0].reason.find("trace"), std::string::npos);
}

TEST(LinkEmulatorNode, PublicEpisodeTraceIsReplayedTurnByTurn) {
  A3_REQUIRE_SHARED(file, "alphabench/eval_runs/anthropic/claude-haiku-4.5/uav/sc-0000-ep-00.json");
  LinkEmulatorConfig config;
  config.trace = load_network_trace(file, 5.0);
  config.net_rate_hz = 1.0;
  LinkEmulatorNode node(config);
  ClientNode client;
  const std::size_t turns = config.trace->points.size();
  for (std::size_t i = 0; i < turns; ++i) {
    client.send_at(static_cast<int64_t>(i) * 5 * kSecond + 2 * kSecond, true, make_message(static_cast<int64_t>(i), "agent", 300));
  }
  run(node, client, static_cast<int64_t>(turns) * 5 * kSecond);
  ASSERT_EQ(client.records.size(), turns);
  for (std::size_t i = 0; i < turns; ++i) {
    const NetworkState& want = config.trace->points[i].state;
    SCOPED_TRACE("turn " + std::to_string(i + 1));
    // The record of the turn's message carries the turn's net vector: the per-turn `net`
    // of an episode written from these records is the trace's.
    EXPECT_EQ(client.records[i].slice, to_string(want.slice));
    EXPECT_EQ(client.records[i].net_lat_ms, want.lat_ms);
    EXPECT_EQ(client.records[i].net_loss_pct, want.loss_pct);
    EXPECT_EQ(client.records[i].net_edge_load, want.edge_load);
    // And the periodic A3_NET at the turn's start shows it too.
    const auto it = std::find_if(client.net.begin(), client.net.end(), [&](const auto& n) {
      return n.utime_us == static_cast<int64_t>(i) * 5 * kSecond + kSecond;
    });
    ASSERT_NE(it, client.net.end());
    EXPECT_EQ(it->slice, to_string(want.slice));
    EXPECT_EQ(it->throughput_mbps, want.throughput_mbps);
  }
}

void request_slice(ClientNode& client, int64_t t_us, const std::string& slice, int64_t id) {
  client.at(t_us, [slice, id](common::Executor& ex, common::Bus& bus) {
    a3lcm::slice_switch_request_t r{};
    r.utime_us = ex.clock().now_us();
    r.request_id = id;
    r.requester = "tool_server";
    r.slice = slice;
    bus.publish(common::channels::kSliceRequest.of(0), r);
  });
}

TEST(LinkEmulatorNode, SliceSwitchTakesEffectAfterTheHandoverAndInFlightMessagesKeepTheirSlice) {
  LinkEmulatorConfig config;
  config.seed = 5;
  config.initial_slice = Slice::kEmbb;
  config.handover_delay_ms = 100.0;
  config.net_rate_hz = 0.0;
  LinkEmulatorNode node(config);
  ClientNode client;
  client.send_at(1 * kSecond, true, make_message(1, "agent", 200));
  request_slice(client, 2 * kSecond, "mMTC", 10);
  client.send_at(2050 * kMs, true, make_message(2, "agent", 200, 20'000'000));  // in flight past the switch
  client.send_at(2100 * kMs, false, make_message(3, "tool_server", 200));
  request_slice(client, 3 * kSecond, "mMTC", 11);
  request_slice(client, 4 * kSecond, "5G", 12);
  run(node, client, 60 * kSecond);

  ASSERT_EQ(client.slice_replies.size(), 3u);
  const auto& accepted = client.slice_replies[0];
  EXPECT_TRUE(accepted.accepted);
  EXPECT_EQ(accepted.request_id, 10);
  EXPECT_EQ(accepted.from_slice, "eMBB");
  EXPECT_EQ(accepted.to_slice, "mMTC");
  EXPECT_EQ(accepted.effective_utime_us, 2100 * kMs);
  EXPECT_TRUE(client.slice_replies[1].accepted);
  EXPECT_EQ(client.slice_replies[1].reason, "already active");
  EXPECT_FALSE(client.slice_replies[2].accepted);
  EXPECT_NE(client.slice_replies[2].reason.find("unknown slice '5G'"), std::string::npos);

  // A3_NET: pending during the handover, switched at its end.
  const auto net_at = [&](int64_t t) {
    const auto it = std::find_if(client.net.begin(), client.net.end(), [t](const auto& n) { return n.utime_us == t; });
    EXPECT_NE(it, client.net.end()) << "no A3_NET at " << t;
    return it == client.net.end() ? a3lcm::network_state_t{} : *it;
  };
  EXPECT_EQ(net_at(2 * kSecond).slice, "eMBB");
  EXPECT_EQ(net_at(2 * kSecond).pending_slice, "mMTC");
  EXPECT_EQ(net_at(2100 * kMs).slice, "mMTC");
  EXPECT_EQ(net_at(2100 * kMs).pending_slice, "");

  ASSERT_EQ(client.records.size(), 3u);
  EXPECT_EQ(client.records[0].slice, "eMBB");
  EXPECT_EQ(client.records[1].slice, "eMBB") << "sent during the handover";
  EXPECT_EQ(client.records[2].slice, "mMTC");
  ASSERT_EQ(client.up_rx.size(), 2u);
  EXPECT_GT(client.up_rx[1].recv_us, 2100 * kMs) << "delivered after the switch";
  EXPECT_EQ(client.up_rx[1].message.slice, "eMBB") << "but keeps the slice it was sent on";
  EXPECT_EQ(client.down_rx.at(0).message.slice, "mMTC");
}

TEST(LinkEmulatorNode, EdgeComputeDelayScalesWithTheEdgeLoad) {
  NetworkTrace trace;
  trace.points = {{0, make_state(Slice::kEmbb, 20, 2, 0.5, 500, 0.6)},
                  {10 * kSecond, make_state(Slice::kEmbb, 20, 2, 0.5, 500, 0.9)},
                  {20 * kSecond, make_state(Slice::kEmbb, 20, 2, 0.5, 500, 0.99)}};
  LinkEmulatorConfig config;
  config.trace = trace;
  LinkEmulatorNode node(config);
  ClientNode client;
  const auto ask = [&client](int64_t t, double work_ms, int64_t id) {
    client.at(t, [work_ms, id](common::Executor& ex, common::Bus& bus) {
      a3lcm::edge_compute_request_t r{};
      r.utime_us = ex.clock().now_us();
      r.request_id = id;
      r.requester = "agent";
      r.work_ms = work_ms;
      bus.publish(common::channels::kEdgeRequest.of(0), r);
    });
  };
  ask(5 * kSecond, 1000.0, 1);
  ask(15 * kSecond, 1000.0, 2);
  ask(25 * kSecond, 1000.0, 3);
  ask(26 * kSecond, -1.0, 4);
  run(node, client, 30 * kSecond);
  ASSERT_EQ(client.edge_replies.size(), 4u);
  EXPECT_NEAR(client.edge_replies[0].delay_ms, 2500.0, 1e-9);
  EXPECT_DOUBLE_EQ(client.edge_replies[0].edge_load, 0.6);
  EXPECT_EQ(client.edge_replies[0].request_id, 1);
  EXPECT_EQ(client.edge_replies[0].slice, "eMBB");
  EXPECT_NEAR(client.edge_replies[1].delay_ms, 10000.0, 1e-6);
  EXPECT_NEAR(client.edge_replies[2].delay_ms, 20000.0, 1e-6) << "load capped at 0.95";
  EXPECT_EQ(client.edge_replies[3].delay_ms, -1.0);
  EXPECT_NE(client.edge_replies[3].error.find("work_ms"), std::string::npos);
  EXPECT_EQ(node.stats().edge_requests, 4u);
}

TEST(LinkEmulatorNode, BadInputIsDroppedWithACountedRecordedReasonAndTheLinkGoesOn) {
  LinkEmulatorConfig config = config_with_trace(make_state(Slice::kUrllc, 7, 0, 0, 95, 0.3));
  config.max_message_bytes = 1 << 20;
  LinkEmulatorNode node(config);
  ClientNode client;
  client.at(kSecond, [](common::Executor&, common::Bus& bus) {
    const uint8_t garbage[] = {0xde, 0xad, 0xbe, 0xef, 1, 2, 3};
    bus.publish_raw(common::channels::kLinkUpTx.of(0).name, garbage, sizeof garbage);
  });
  client.send_at(kSecond + 1, true, make_message(1, "agent", 100, -5));
  client.send_at(kSecond + 2, true, make_message(2, "agent", 100, 10));
  client.send_at(kSecond + 3, true, make_message(3, "agent", 100, 2 << 20));
  client.send_at(kSecond + 4, true, make_message(4, "agent", 100));
  client.send_at(kSecond + 5, false, make_message(5, "tool_server", 100));
  run(node, client, 2 * kSecond);

  const DirectionStats& up = node.stats().up;
  EXPECT_EQ(up.received, 5u);
  EXPECT_EQ(up.dropped[static_cast<int>(DropReason::kUndecodable)], 1u);
  EXPECT_EQ(up.dropped[static_cast<int>(DropReason::kBadSize)], 2u);
  EXPECT_EQ(up.dropped[static_cast<int>(DropReason::kOversized)], 1u);
  EXPECT_EQ(up.delivered, 1u);
  ASSERT_EQ(client.up_rx.size(), 1u);
  EXPECT_EQ(client.up_rx[0].message.message_id, 4);
  EXPECT_EQ(client.down_rx.size(), 1u);

  ASSERT_EQ(client.records.size(), 6u) << "every message has a record, dropped ones too";
  std::vector<std::string> reasons;
  for (const auto& r : client.records) {
    if (r.outcome == a3lcm::link_record_t::DROPPED) {
      reasons.push_back(r.drop_reason);
      EXPECT_EQ(r.delivery_utime_us, -1);
    }
  }
  ASSERT_EQ(reasons.size(), 4u);
  EXPECT_EQ(reasons[0], "undecodable: 7 bytes that do not decode as link_message_t");
  EXPECT_EQ(reasons[1], "bad_size: payload_size_bytes -5 is negative");
  EXPECT_EQ(reasons[2], "bad_size: payload_size_bytes 10 is less than the 100-byte payload");
  EXPECT_EQ(reasons[3], "oversized: 2097152 bytes > max_message_bytes 1048576");
}

TEST(LinkEmulatorNode, FullBuffersDropTheTail) {
  LinkEmulatorConfig config = config_with_trace(make_state(Slice::kMmtc, 1000, 0, 0, 2.3, 0.7));
  config.max_pending_messages = 10;
  config.max_backlog_s = 5.0;
  LinkEmulatorNode node(config);
  ClientNode client;
  for (int i = 0; i < 20; ++i) client.send_at(kSecond, true, make_message(i, "agent", 100));
  client.send_at(10 * kSecond, false, make_message(100, "tool_server", 100, 5'000'000));
  client.send_at(11 * kSecond, false, make_message(101, "tool_server", 100));
  run(node, client, 60 * kSecond);
  EXPECT_EQ(node.stats().up.delivered, 10u);
  EXPECT_EQ(node.stats().up.dropped[static_cast<int>(DropReason::kQueueFull)], 10u);
  EXPECT_EQ(node.stats().down.delivered, 1u);
  EXPECT_EQ(node.stats().down.dropped[static_cast<int>(DropReason::kQueueFull)], 1u)
      << "behind 17 s of image: over the 5 s backlog limit";
  EXPECT_EQ(node.stats().up.max_pending, 10u);
}

TEST(LinkEmulatorNode, LossFollowsTheNetworkVector) {
  LinkEmulatorNode node(config_with_trace(make_state(Slice::kMmtc, 50, 5, 5.0, 1000, 0.7)));
  ClientNode client;
  const int n = 100000;
  for (int i = 0; i < n; ++i) client.send_at(kSecond + i * 100, i % 2 == 0, make_message(i, "agent", 50));
  run(node, client, 20 * kSecond);
  const uint64_t lost = node.stats().up.lost + node.stats().down.lost;
  EXPECT_NEAR(static_cast<double>(lost) / n, 0.05, 0.005);
  EXPECT_EQ(client.up_rx.size() + client.down_rx.size() + lost, static_cast<uint64_t>(n));
  uint64_t lost_records = 0;
  for (const auto& r : client.records) lost_records += r.outcome == a3lcm::link_record_t::LOST;
  EXPECT_EQ(lost_records, lost);
}

TEST(LinkEmulatorNode, NetIsPublishedAtTheConfiguredRate) {
  LinkEmulatorConfig config = config_with_trace(make_state(Slice::kEmbb, 15, 2, 0.3, 600, 0.5));
  config.net_rate_hz = 5.0;
  LinkEmulatorNode node(config);
  ClientNode client;
  run(node, client, 10 * kSecond);
  // One at start, then every 200 ms through 10 s.
  ASSERT_EQ(client.net.size(), 51u);
  for (std::size_t i = 1; i < client.net.size(); ++i) {
    EXPECT_EQ(client.net[i].utime_us, static_cast<int64_t>(i) * 200 * kMs);
  }
}

TEST(LinkEmulatorNode, RecordSinksSeeEveryRecordAndThePublicationCanBeTurnedOff) {
  LinkEmulatorConfig config = config_with_trace(make_state(Slice::kEmbb, 15, 2, 0.3, 600, 0.5));
  config.publish_records = false;
  LinkEmulatorNode node(config);
  std::vector<a3lcm::link_record_t> sunk;
  node.add_record_sink([&sunk](const a3lcm::link_record_t& r) { sunk.push_back(r); });
  ClientNode client;
  for (int i = 0; i < 10; ++i) client.send_at(kSecond + i, i % 2, make_message(i, "x", 10));
  run(node, client, 3 * kSecond);
  EXPECT_EQ(sunk.size(), 10u);
  EXPECT_TRUE(client.records.empty());
  EXPECT_EQ(node.stats().records, 10u);
}

TEST(LinkEmulatorNode, BadConfigIsRefusedNamingTheField) {
  LinkEmulatorConfig config;
  config.handover_delay_ms = -1.0;
  try {
    LinkEmulatorNode node(config);
    FAIL() << "accepted a negative handover delay";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("handover_delay_ms: -1 must be"), std::string::npos) << e.what();
  }
  LinkEmulatorConfig impossible;
  impossible.min_dwell_s = 100.0;  // above the 30 s degraded mean
  EXPECT_THROW(LinkEmulatorNode node(impossible), std::invalid_argument);
}

}  // namespace
}  // namespace a3::linkemu
