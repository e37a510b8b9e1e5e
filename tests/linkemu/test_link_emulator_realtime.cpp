// The link emulator on the real-time runtime: on its own thread with memq:// (one process),
// and across two LCM buses over udpm:// as two processes would use it. Bounds are
// generous and the checks are about behaviour: everything arrives, never before its
// scheduled delivery time, in order, with the emulated latency. The udpm test is skipped
// with the fix-it message when multicast is not looped back (fails with A3_REQUIRE_UDPM=1).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <random>
#include <thread>

#include "common/clock.hpp"
#include "common/runtime.hpp"
#include "linkemu/link_emulator_node.hpp"
#include "tests/linkemu/linkemu_test_util.hpp"
#include "tests/test_support.hpp"

namespace a3::linkemu {
namespace {

using test::ClientNode;
using test::make_message;
using test::make_state;
constexpr int64_t kMs = 1000;

void wait_until(const common::Clock& clock, int64_t t_us) {
  while (clock.now_us() < t_us) std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

// Every delivery: not early, not absurdly late, latency at least the jitter floor, FIFO.
void expect_timely(const std::vector<test::Received>& rx, std::size_t expected, int64_t floor_us) {
  ASSERT_EQ(rx.size(), expected);
  for (std::size_t i = 0; i < rx.size(); ++i) {
    const auto& r = rx[i];
    EXPECT_GE(r.recv_us, r.message.utime_us) << "message " << r.message.message_id << " arrived early";
    // Generous: a loaded 2-CPU machine can hold a thread off its CPU for tens of ms.
    EXPECT_LT(r.recv_us - r.message.utime_us, 500 * kMs) << "message " << r.message.message_id;
    EXPECT_GE(r.message.utime_us - r.message.sent_utime_us, floor_us);
    if (i > 0) {
      EXPECT_GT(r.message.message_id, rx[i - 1].message.message_id);
    }
  }
}

TEST(LinkEmulatorRealTime, RelaysOnItsOwnThreadWithTheEmulatedTiming) {
  LinkEmulatorConfig config;
  config.trace = test::constant_trace(make_state(Slice::kEmbb, 20, 2, 0, 100, 0.5));
  LinkEmulatorNode node(config);
  const common::WallClock clock;
  common::RealTimeNodeThread thread(node, clock, "memq://");
  ClientNode client;
  for (int i = 0; i < 200; ++i) {
    client.send_at(200 * kMs + i * 5 * kMs, true, make_message(i, "agent", 300));
    client.send_at(200 * kMs + i * 5 * kMs + 1, false, make_message(1000 + i, "tool_server", 300));
  }
  client.start(thread.executor(), thread.bus());
  thread.start();
  wait_until(clock, 3000 * kMs);  // the last message is due at ~1.2 s
  thread.stop_and_join();
  ASSERT_EQ(thread.failure(), "");

  // Latency 20 ms with 2 ms jitter: never below 18 ms.
  expect_timely(client.up_rx, 200, 18 * kMs);
  expect_timely(client.down_rx, 200, 18 * kMs);
  EXPECT_EQ(node.stats().up.delivered, 200u);
  EXPECT_EQ(node.delivery_lateness_us().size(), 400u);
  EXPECT_GT(client.net.size(), 10u) << "A3_NET at 10 Hz";
}

TEST(LinkEmulatorRealTime, RelaysBetweenTwoLcmBusesOverUdpm) {
  const std::string url = a3::test::private_udpm_url();
  const char* require_env = std::getenv("A3_REQUIRE_UDPM");
  const bool required = require_env != nullptr && std::string(require_env) == "1";
  try {
    common::LcmBus probe(url);
    probe.check_loopback(1000);
  } catch (const std::exception& e) {
    const std::string message = std::string("LCM over ") + url + " does not work on this host: " + e.what();
    if (required) FAIL() << message;
    GTEST_SKIP() << message << "\n(set A3_REQUIRE_UDPM=1 to make its absence a failure)";
  }
  // Channels no other run on this host uses (udpm traffic is host-wide).
  std::mt19937_64 gen(std::random_device{}());
  LinkEmulatorConfig config;
  config.channels = LinkChannels{}.with_suffix("_T" + std::to_string(::getpid()) + "_" + std::to_string(gen() % 1000000));
  config.trace = test::constant_trace(make_state(Slice::kUrllc, 8, 1, 0, 95, 0.3));
  LinkEmulatorNode node(config);
  ClientNode client(config.channels);
  for (int i = 0; i < 100; ++i) {
    client.send_at(300 * kMs + i * 4 * kMs, i % 2 == 0, make_message(i, "agent", 200));
  }
  const common::WallClock clock;
  common::RealTimeNodeThread node_thread(node, clock, url);
  common::RealTimeNodeThread client_thread(client, clock, url);
  node_thread.start();
  client_thread.start();
  wait_until(clock, 2500 * kMs);  // the last message is due at ~0.7 s
  client_thread.stop_and_join();
  node_thread.stop_and_join();
  expect_timely(client.up_rx, 50, 7 * kMs);
  expect_timely(client.down_rx, 50, 7 * kMs);
  EXPECT_EQ(node.stats().up.received + node.stats().down.received, 100u);
  EXPECT_EQ(client.records.size(), 100u) << "records cross the bus too";
}

}  // namespace
}  // namespace a3::linkemu
