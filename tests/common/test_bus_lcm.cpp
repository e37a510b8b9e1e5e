// The typed Bus wrapper on LcmBus: URL resolution (LCM_DEFAULT_URL, default ttl=0),
// memq:// in one process (delivery, receive clock, exact channel names, unsubscribe,
// decode failures), and udpm:// between two buses as two processes would use it.
// The udpm test needs multicast looped back on this host; it is skipped with the fix-it
// message when that is missing, or fails when A3_REQUIRE_UDPM=1.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "a3lcm/link_message_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/clock.hpp"
#include "common/lcm_bus.hpp"
#include "common/log.hpp"
#include "tests/common/bus_test_messages.hpp"
#include "tests/common/common_test_util.hpp"
#include "tests/test_support.hpp"

namespace a3::common {
namespace {

const std::string kUdpmUrl = a3::test::private_udpm_url();

// A channel name no other test run on this host uses (udpm traffic is host-wide).
std::string unique_channel(const std::string& base) {
  static std::mt19937_64 gen(std::random_device{}());
  return base + "_" + std::to_string(::getpid()) + "_" + std::to_string(gen() % 1000000000);
}

// Dispatches until pred() holds or timeout_ms passes.
template <typename Pred>
bool pump_until(LcmBus& bus, Pred pred, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (!pred() && std::chrono::steady_clock::now() < deadline) bus.handle_timeout(10);
  return pred();
}

TEST(ResolveLcmUrl, RequestedUrlWins) {
  test::ScopedEnv env("LCM_DEFAULT_URL", "memq://");
  EXPECT_EQ(resolve_lcm_url("udpm://239.255.76.67:7668?ttl=0"), "udpm://239.255.76.67:7668?ttl=0");
}

TEST(ResolveLcmUrl, HonoursLcmDefaultUrl) {
  test::ScopedEnv env("LCM_DEFAULT_URL", "memq://");
  EXPECT_EQ(resolve_lcm_url(""), "memq://");
  const LcmBus bus;
  EXPECT_EQ(bus.url(), "memq://") << "LcmBus() uses LCM_DEFAULT_URL like every LCM tool";
}

TEST(AnswersLcmUrl, UdpmAnswersOnTheNextPortOfTheSameGroup) {
  EXPECT_EQ(answers_lcm_url("udpm://239.255.76.67:7668?ttl=0"), "udpm://239.255.76.67:7669?ttl=0");
  EXPECT_EQ(answers_lcm_url("udpm://239.255.76.67:7681"), "udpm://239.255.76.67:7682");
  EXPECT_EQ(answers_lcm_url("udpm://239.255.76.67?ttl=0&recv_buf_size=2097152"),
            "udpm://239.255.76.67:7668?ttl=0&recv_buf_size=2097152")
      << "no port: LCM's 7667, answered on 7668";
}

TEST(AnswersLcmUrl, OtherTransportsAnswerOnTheirOwnUrl) {
  EXPECT_EQ(answers_lcm_url("memq://"), "memq://");
  EXPECT_EQ(answers_lcm_url("file:///tmp/x.lcmlog?mode=w"), "file:///tmp/x.lcmlog?mode=w");
}

TEST(AnswersLcmUrl, ABadPortIsNamed) {
  for (const char* url : {"udpm://239.255.76.67:76x8?ttl=0", "udpm://239.255.76.67:65535", "udpm://239.255.76.67:"}) {
    try {
      answers_lcm_url(url);
      ADD_FAILURE() << url << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(url), std::string::npos) << e.what();
    }
  }
}

TEST(ResolveLcmUrl, DefaultIsUdpmWithTtlZero) {
  {
    test::ScopedEnv unset("LCM_DEFAULT_URL", std::nullopt);
    EXPECT_EQ(resolve_lcm_url(""), kDefaultLcmUrl);
  }
  {
    test::ScopedEnv empty("LCM_DEFAULT_URL", "");
    EXPECT_EQ(resolve_lcm_url(""), kDefaultLcmUrl) << "an empty variable means unset";
  }
  const std::string url = kDefaultLcmUrl;
  EXPECT_EQ(url.rfind("udpm://", 0), 0u) << url;
  EXPECT_NE(url.find("ttl=0"), std::string::npos) << url << ": must never leave the host";
  EXPECT_EQ(url.find("ttl=1"), std::string::npos) << url;
}

TEST(LcmBus, MulticastHintSaysHowToFixTheHost) {
  const std::string hint = lcm_multicast_hint();
  EXPECT_NE(hint.find("ip link set lo multicast on"), std::string::npos) << hint;
  EXPECT_NE(hint.find("ip route add 239.255.76.67/32 dev lo"), std::string::npos) << hint;
  EXPECT_NE(hint.find("--runtime virtual"), std::string::npos) << hint;
  EXPECT_EQ(hint.find("memq"), std::string::npos) << "memq:// cannot carry a rig run: " << hint;
}

TEST(LcmBus, UnknownProviderIsRefusedNamingTheUrl) {
  try {
    const LcmBus bus("nosuchprovider://x");
    ADD_FAILURE() << "created a bus on an unknown provider";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nosuchprovider://x"), std::string::npos) << e.what();
  }
}

TEST(LcmBusMemq, TypedRoundTripStampedWithTheReceiveClock) {
  const VirtualClock recv_clock(987'654);
  LcmBus bus("memq://", &recv_clock);
  EXPECT_EQ(bus.url(), "memq://");
  std::vector<a3lcm::vehicle_state_t> got;
  std::vector<int64_t> stamps;
  bus.subscribe<a3lcm::vehicle_state_t>("A3_STATE",
                                        [&](const a3lcm::vehicle_state_t& m, int64_t t) {
                                          got.push_back(m);
                                          stamps.push_back(t);
                                        });
  const a3lcm::vehicle_state_t sent = test::make_state(42);
  ASSERT_TRUE(bus.publish("A3_STATE", sent));
  EXPECT_TRUE(got.empty()) << "delivery happens when the bus is handled";
  EXPECT_EQ(bus.handle_ready(), 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(test::encode_bytes(got[0]), test::encode_bytes(sent));
  EXPECT_EQ(stamps[0], 987'654);
  EXPECT_FALSE(bus.handle_timeout(20)) << "nothing left to deliver";
  EXPECT_EQ(bus.publish_failures(), 0u);
}

TEST(LcmBusMemq, WithoutAReceiveClockUsesLcmsTimestamp) {
  LcmBus bus("memq://");
  int64_t stamp = -1;
  bus.subscribe<a3lcm::vehicle_state_t>(
      "A3_STATE", [&](const a3lcm::vehicle_state_t&, int64_t t) { stamp = t; });
  const auto before = std::chrono::duration_cast<std::chrono::microseconds>(
                          std::chrono::system_clock::now().time_since_epoch())
                          .count();
  bus.publish("A3_STATE", test::make_state(1));
  ASSERT_TRUE(bus.handle_timeout(1000));
  // LCM stamps with its own (epoch) clock; it is at least somewhere near "now".
  EXPECT_GT(stamp, before - 60'000'000);
  EXPECT_LT(stamp, before + 60'000'000);
}

TEST(LcmBusMemq, FifoOnAChannelAndExactChannelNames) {
  LcmBus bus("memq://");
  std::vector<int64_t> exact, dotted;
  bus.subscribe<a3lcm::link_message_t>(
      "A3_LINK", [&](const a3lcm::link_message_t& m, int64_t) { exact.push_back(m.message_id); });
  // LCM subscriptions are regular expressions; ours match the literal name only.
  bus.subscribe<a3lcm::link_message_t>(
      "A3.LINK", [&](const a3lcm::link_message_t& m, int64_t) { dotted.push_back(m.message_id); });
  std::vector<int64_t> sent;
  for (int64_t id = 1; id <= 20; ++id) {
    bus.publish("A3_LINK", test::make_link_message(id, "x"));
    sent.push_back(id);
  }
  bus.publish("A3_LINK_SUFFIX", test::make_link_message(100, "not a prefix match"));
  bus.publish("A3.LINK", test::make_link_message(200, "dotted"));
  // memq drops A3_LINK_SUFFIX at once (no subscriber matches it); the other 21 are delivered.
  EXPECT_EQ(bus.handle_ready(), 21);
  EXPECT_EQ(exact, sent);
  EXPECT_EQ(dotted, (std::vector<int64_t>{200}));
}

// A steady stream must not keep one handle_ready() call forever: it hands back after a
// bounded batch so the executor's timers run, and the rest waits for the next call.
TEST(LcmBusMemq, HandleReadyDispatchesABoundedBatch) {
  LcmBus bus("memq://");
  int received = 0;
  bus.subscribe<a3lcm::link_message_t>("A3_LINK", [&](const a3lcm::link_message_t&, int64_t) { ++received; });
  for (int64_t id = 1; id <= 200; ++id) bus.publish("A3_LINK", test::make_link_message(id, "x"));
  const int first = bus.handle_ready();
  EXPECT_GT(first, 0);
  EXPECT_LT(first, 200);
  int calls = 1;
  while (received < 200 && calls < 100) {
    bus.handle_ready();
    ++calls;
  }
  EXPECT_EQ(received, 200);
}

TEST(LcmBusMemq, UnsubscribeStopsDelivery) {
  LcmBus bus("memq://");
  int a = 0, b = 0;
  const SubscriptionId ida = bus.subscribe<a3lcm::vehicle_state_t>(
      "A3_STATE", [&](const a3lcm::vehicle_state_t&, int64_t) { ++a; });
  bus.subscribe<a3lcm::vehicle_state_t>("A3_STATE",
                                        [&](const a3lcm::vehicle_state_t&, int64_t) { ++b; });
  bus.publish("A3_STATE", test::make_state(1));
  bus.handle_ready();
  bus.unsubscribe(ida);
  bus.unsubscribe(ida);   // twice: ignored
  bus.unsubscribe(777);   // unknown: ignored
  bus.publish("A3_STATE", test::make_state(2));
  bus.handle_ready();
  EXPECT_EQ(a, 1);
  EXPECT_EQ(b, 2);
}

TEST(LcmBusMemq, MessagesThatDoNotDecodeAreDroppedAndCounted) {
  const LogLevel saved = log_level();
  set_log_level(LogLevel::kOff);
  LcmBus bus("memq://");
  std::vector<int64_t> got;
  int events = 0, links = 0;
  bus.subscribe<a3lcm::vehicle_state_t>(
      "A3_STATE", [&](const a3lcm::vehicle_state_t& m, int64_t) { got.push_back(m.utime_us); });
  bus.subscribe<a3lcm::episode_event_t>("A3_EPISODE",
                                        [&](const a3lcm::episode_event_t&, int64_t) { ++events; });
  bus.subscribe<a3lcm::link_message_t>("A3_LINK_UP_RX",
                                       [&](const a3lcm::link_message_t&, int64_t) { ++links; });
  const std::vector<uint8_t> garbage = {0xDE, 0xAD, 0xBE, 0xEF, 0, 1, 2, 3, 4};
  bus.publish_raw("A3_STATE", garbage.data(), garbage.size());
  bus.publish("A3_STATE", test::make_link_message(1, "wrong type"));
  // Malformed length fields must be counted, not thrown through LCM's C callback.
  const auto bad_string = test::episode_event_with_zero_string_length();
  const auto bad_payload = test::link_message_with_negative_payload_length();
  bus.publish_raw("A3_EPISODE", bad_string.data(), bad_string.size());
  bus.publish_raw("A3_LINK_UP_RX", bad_payload.data(), bad_payload.size());
  bus.publish("A3_STATE", test::make_state(7));
  EXPECT_EQ(bus.handle_ready(), 5);
  set_log_level(saved);
  EXPECT_EQ(got, (std::vector<int64_t>{7}));
  EXPECT_EQ(events, 0);
  EXPECT_EQ(links, 0);
  EXPECT_EQ(bus.decode_failures(), 4u);
}

TEST(LcmBusMemq, CheckLoopbackPassesInOneProcess) {
  LcmBus bus("memq://");
  EXPECT_NO_THROW(bus.check_loopback(500));
  // The probe subscription is gone afterwards: a later message on it reaches no one.
  int seen = 0;
  bus.subscribe_raw("A3_OTHER", [&](const std::string&, const uint8_t*, std::size_t, int64_t) {
    ++seen;
  });
  const uint8_t one = 1;
  bus.publish_raw("A3_OTHER", &one, 1);
  bus.handle_ready();
  EXPECT_EQ(seen, 1);
}

// udpm: two buses, each as one process would have it. Skips (or fails with
// A3_REQUIRE_UDPM=1) with the fix-it message when the host has no multicast loopback.
TEST(LcmBusUdpm, VehicleStateCrossesBetweenTwoBuses) {
  const char* require_env = std::getenv("A3_REQUIRE_UDPM");
  const bool required = require_env != nullptr && std::string(require_env) == "1";
  std::unique_ptr<LcmBus> sender, receiver;
  try {
    sender = std::make_unique<LcmBus>(kUdpmUrl);
    receiver = std::make_unique<LcmBus>(kUdpmUrl);
    sender->check_loopback(1000);
    receiver->check_loopback(1000);
  } catch (const std::exception& e) {
    const std::string message =
        std::string("LCM over ") + kUdpmUrl + " does not work on this host: " + e.what();
    if (required) FAIL() << message;
    GTEST_SKIP() << message
                 << "\n(set up multicast on lo as above to run this test; "
                    "set A3_REQUIRE_UDPM=1 to make its absence a failure)";
  }
  EXPECT_EQ(sender->url(), kUdpmUrl);

  const std::string channel = unique_channel("A3_TEST_STATE");
  std::vector<a3lcm::vehicle_state_t> got;
  receiver->subscribe<a3lcm::vehicle_state_t>(
      channel, [&](const a3lcm::vehicle_state_t& m, int64_t) { got.push_back(m); });
  std::vector<a3lcm::vehicle_state_t> sent;
  for (int i = 0; i < 5; ++i) {
    sent.push_back(test::make_state(1000 + i));
    ASSERT_TRUE(sender->publish(channel, sent.back()));
  }
  ASSERT_TRUE(pump_until(*receiver, [&] { return got.size() >= sent.size(); }, 3000))
      << "received " << got.size() << " of " << sent.size() << " over " << kUdpmUrl;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(test::encode_bytes(got[i]), test::encode_bytes(sent[i])) << "message " << i;
  }
  EXPECT_EQ(got[4].utime_us, 1004);
  EXPECT_EQ(receiver->decode_failures(), 0u);
  EXPECT_EQ(sender->publish_failures(), 0u);
}

}  // namespace
}  // namespace a3::common
