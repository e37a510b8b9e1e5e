// The typed Bus wrapper on VirtualBus: delivery through the scheduler at the current virtual
// time, FIFO per channel, channel isolation, unsubscribe, copies of the bytes, and messages
// that do not decode dropped and counted (never thrown into the scheduler).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/link_message_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/log.hpp"
#include "common/virtual_bus.hpp"
#include "common/virtual_scheduler.hpp"
#include "tests/common/bus_test_messages.hpp"

namespace a3::common {
namespace {

class VirtualBusTest : public ::testing::Test {
 protected:
  VirtualScheduler scheduler_;
  VirtualBus bus_{scheduler_};
};

TEST_F(VirtualBusTest, TypedMessageArrivesDecodedThroughTheScheduler) {
  std::vector<a3lcm::vehicle_state_t> got;
  std::vector<int64_t> recv_times;
  bus_.subscribe<a3lcm::vehicle_state_t>(
      "A3_STATE", [&](const a3lcm::vehicle_state_t& m, int64_t recv_utime_us) {
        got.push_back(m);
        recv_times.push_back(recv_utime_us);
      });
  scheduler_.run_until(2500);
  const a3lcm::vehicle_state_t sent = test::make_state(2400);
  EXPECT_TRUE(bus_.publish("A3_STATE", sent));
  EXPECT_TRUE(got.empty()) << "delivery is a scheduler event, not a direct call";
  EXPECT_EQ(scheduler_.pending(), 1u);
  scheduler_.run_until(2500);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(recv_times[0], 2500) << "delivered at the current virtual time";
  EXPECT_EQ(test::encode_bytes(got[0]), test::encode_bytes(sent));
  EXPECT_EQ(got[0].p_W_m[2], sent.p_W_m[2]);
  EXPECT_EQ(got[0].crashed, true);
  EXPECT_EQ(bus_.messages_published(), 1u);
  EXPECT_EQ(bus_.decode_failures(), 0u);
}

TEST_F(VirtualBusTest, DeliveryComesAfterEventsAlreadyDueAtThatTime) {
  std::vector<std::string> order;
  bus_.subscribe<a3lcm::vehicle_state_t>(
      "A3_STATE", [&](const a3lcm::vehicle_state_t&, int64_t) { order.push_back("delivery"); });
  scheduler_.schedule_at(100, [&] {
    order.push_back("publisher");
    bus_.publish("A3_STATE", test::make_state(100));
  });
  scheduler_.schedule_at(100, [&] { order.push_back("other@100"); });
  scheduler_.schedule_at(101, [&] { order.push_back("other@101"); });
  scheduler_.run_until(200);
  EXPECT_EQ(order, (std::vector<std::string>{"publisher", "other@100", "delivery", "other@101"}));
}

TEST_F(VirtualBusTest, FifoPerChannelAndEverySubscriberGetsEverything) {
  std::vector<int64_t> first, second;
  std::vector<std::string> who;
  bus_.subscribe<a3lcm::link_message_t>("A3_LINK_UP_TX",
                                        [&](const a3lcm::link_message_t& m, int64_t) {
                                          first.push_back(m.message_id);
                                          who.push_back("s1");
                                        });
  bus_.subscribe<a3lcm::link_message_t>("A3_LINK_UP_TX",
                                        [&](const a3lcm::link_message_t& m, int64_t) {
                                          second.push_back(m.message_id);
                                          who.push_back("s2");
                                        });
  std::vector<int64_t> sent;
  for (int64_t id = 1; id <= 50; ++id) {
    bus_.publish("A3_LINK_UP_TX", test::make_link_message(id, "payload " + std::to_string(id)));
    sent.push_back(id);
  }
  scheduler_.run_until(0);
  EXPECT_EQ(first, sent);
  EXPECT_EQ(second, sent);
  // Per message, subscribers in subscription order.
  ASSERT_EQ(who.size(), 100u);
  for (std::size_t i = 0; i < who.size(); i += 2) {
    EXPECT_EQ(who[i], "s1");
    EXPECT_EQ(who[i + 1], "s2");
  }
}

TEST_F(VirtualBusTest, ChannelsAreSeparate) {
  int state = 0, status = 0;
  bus_.subscribe<a3lcm::vehicle_state_t>("A3_STATE",
                                         [&](const a3lcm::vehicle_state_t&, int64_t) { ++state; });
  bus_.subscribe<a3lcm::fc_status_t>("A3_FC_STATUS",
                                     [&](const a3lcm::fc_status_t&, int64_t) { ++status; });
  bus_.publish("A3_STATE", test::make_state(1));
  bus_.publish("A3_STATE", test::make_state(2));
  bus_.publish("A3_STATE_EXTRA", test::make_state(3));  // a different channel, not a prefix match
  scheduler_.run_until(10);
  EXPECT_EQ(state, 2);
  EXPECT_EQ(status, 0);
  EXPECT_EQ(bus_.decode_failures(), 0u);
}

TEST_F(VirtualBusTest, UnsubscribeStopsDeliveryIncludingMessagesInFlight) {
  int kept = 0, dropped = 0;
  bus_.subscribe<a3lcm::vehicle_state_t>("A3_STATE",
                                         [&](const a3lcm::vehicle_state_t&, int64_t) { ++kept; });
  const SubscriptionId id = bus_.subscribe<a3lcm::vehicle_state_t>(
      "A3_STATE", [&](const a3lcm::vehicle_state_t&, int64_t) { ++dropped; });
  bus_.publish("A3_STATE", test::make_state(1));
  scheduler_.run_until(1);
  EXPECT_EQ(dropped, 1);
  bus_.publish("A3_STATE", test::make_state(2));  // in flight...
  bus_.unsubscribe(id);                            // ...when the subscriber leaves
  bus_.publish("A3_STATE", test::make_state(3));
  scheduler_.run_until(2);
  EXPECT_EQ(dropped, 1);
  EXPECT_EQ(kept, 3);
  bus_.unsubscribe(id);     // twice: ignored
  bus_.unsubscribe(4242);   // unknown: ignored
}

TEST_F(VirtualBusTest, HandlerMayUnsubscribeItself) {
  int calls = 0;
  SubscriptionId id = 0;
  id = bus_.subscribe<a3lcm::vehicle_state_t>("A3_STATE",
                                              [&](const a3lcm::vehicle_state_t&, int64_t) {
                                                ++calls;
                                                bus_.unsubscribe(id);
                                              });
  bus_.publish("A3_STATE", test::make_state(1));
  bus_.publish("A3_STATE", test::make_state(2));
  scheduler_.run_until(1);
  EXPECT_EQ(calls, 1);
}

TEST_F(VirtualBusTest, PublishedBytesAreCopied) {
  std::vector<uint8_t> bytes = test::encode_bytes(test::make_state(1234));
  int64_t got = 0;
  bus_.subscribe<a3lcm::vehicle_state_t>(
      "A3_STATE", [&](const a3lcm::vehicle_state_t& m, int64_t) { got = m.utime_us; });
  bus_.publish_raw("A3_STATE", bytes.data(), bytes.size());
  std::fill(bytes.begin(), bytes.end(), 0);  // the publisher reuses its buffer
  scheduler_.run_until(0);
  EXPECT_EQ(got, 1234);
}

TEST_F(VirtualBusTest, MessagesThatDoNotDecodeAreDroppedAndCounted) {
  const LogLevel saved = log_level();
  set_log_level(LogLevel::kOff);  // the warnings are expected here
  std::vector<int64_t> got;
  bus_.subscribe<a3lcm::vehicle_state_t>(
      "A3_STATE", [&](const a3lcm::vehicle_state_t& m, int64_t) { got.push_back(m.utime_us); });

  const std::vector<uint8_t> garbage = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  bus_.publish_raw("A3_STATE", garbage.data(), garbage.size());
  bus_.publish("A3_STATE", test::make_link_message(1, "wrong type"));  // other fingerprint
  std::vector<uint8_t> truncated = test::encode_bytes(test::make_state(5));
  truncated.resize(truncated.size() - 1);
  bus_.publish_raw("A3_STATE", truncated.data(), truncated.size());
  bus_.publish_raw("A3_STATE", nullptr, 0);
  bus_.publish("A3_STATE", test::make_state(99));  // a good one still gets through
  scheduler_.run_until(0);
  set_log_level(saved);

  EXPECT_EQ(got, (std::vector<int64_t>{99}));
  EXPECT_EQ(bus_.decode_failures(), 4u);
}

TEST_F(VirtualBusTest, MalformedLengthFieldsAreCountedNotThrown) {
  const LogLevel saved = log_level();
  set_log_level(LogLevel::kOff);
  int events = 0, links = 0;
  bus_.subscribe<a3lcm::episode_event_t>("A3_EPISODE",
                                         [&](const a3lcm::episode_event_t&, int64_t) { ++events; });
  bus_.subscribe<a3lcm::link_message_t>("A3_LINK_UP_RX",
                                        [&](const a3lcm::link_message_t&, int64_t) { ++links; });
  const auto bad_string = test::episode_event_with_zero_string_length();
  const auto bad_payload = test::link_message_with_negative_payload_length();
  bus_.publish_raw("A3_EPISODE", bad_string.data(), bad_string.size());
  bus_.publish_raw("A3_LINK_UP_RX", bad_payload.data(), bad_payload.size());
  EXPECT_NO_THROW(scheduler_.run_until(0)) << "a bad message must not end the run";
  set_log_level(saved);
  EXPECT_EQ(events, 0);
  EXPECT_EQ(links, 0);
  EXPECT_EQ(bus_.decode_failures(), 2u);
}

TEST_F(VirtualBusTest, NothingIsScheduledWithoutSubscribers) {
  EXPECT_TRUE(bus_.publish("A3_STATE", test::make_state(1)));
  EXPECT_EQ(scheduler_.pending(), 0u);
  EXPECT_EQ(bus_.messages_published(), 1u);
}

}  // namespace
}  // namespace a3::common
