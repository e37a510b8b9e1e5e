// The typed Bus wrapper on VirtualBus: delivery through the scheduler at the current virtual
// time, FIFO per channel, channel isolation, unsubscribe, copies of the bytes, and messages
// that do not decode dropped and counted (never thrown into the scheduler). The raw bus:
// one order across channels, one event per message, a handler that publishes or throws, a bus
// destroyed with deliveries pending.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
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

// Raw bytes {tag, fill...} of the given size, and the tag of received bytes.
std::vector<uint8_t> tagged(uint8_t tag, std::size_t size) {
  std::vector<uint8_t> bytes(size, static_cast<uint8_t>(tag ^ 0xFF));
  bytes[0] = tag;
  return bytes;
}

bool intact(const uint8_t* data, std::size_t size) {
  for (std::size_t i = 1; i < size; ++i) {
    if (data[i] != static_cast<uint8_t>(data[0] ^ 0xFF)) return false;
  }
  return true;
}

TEST_F(VirtualBusTest, DeliveriesRunInPublishOrderAcrossChannelsAndAroundAnUnsubscribe) {
  std::vector<std::string> got;
  auto record = [&got](const std::string& who) {
    return [&got, who](const std::string& ch, const uint8_t* data, std::size_t, int64_t) {
      got.push_back(who + ":" + ch + std::to_string(data[0]));
    };
  };
  bus_.subscribe_raw("A", record("x"));
  const SubscriptionId leaving = bus_.subscribe_raw("B", record("y"));
  bus_.subscribe_raw("B", record("z"));
  for (uint8_t i = 1; i <= 2; ++i) {
    const auto a = tagged(i, 4), b = tagged(static_cast<uint8_t>(10 + i), 4);
    bus_.publish_raw("A", a.data(), a.size());
    bus_.publish_raw("B", b.data(), b.size());
  }
  bus_.unsubscribe(leaving);  // two deliveries to it are in flight
  const auto last = tagged(3, 4);
  bus_.publish_raw("A", last.data(), last.size());
  scheduler_.run_until(0);
  EXPECT_EQ(got, (std::vector<std::string>{"x:A1", "z:B11", "x:A2", "z:B12", "x:A3"}));
  EXPECT_EQ(scheduler_.pending(), 0u);
}

// A handler that publishes (more, and larger, messages than the one it reads) while it still
// reads its own: the bytes it was given stay as they were sent until it returns.
TEST_F(VirtualBusTest, AHandlerThatPublishesKeepsReadingItsOwnBytes) {
  std::vector<int> tags;
  int corrupted = 0;
  bus_.subscribe_raw("A", [&](const std::string&, const uint8_t* data, std::size_t size, int64_t) {
    tags.push_back(data[0]);
    if (data[0] < 5) {
      for (uint8_t k = 1; k <= 3; ++k) {
        const auto more = tagged(static_cast<uint8_t>(data[0] * 3 + k), 64 * k);
        bus_.publish_raw("A", more.data(), more.size());
      }
    }
    corrupted += intact(data, size) ? 0 : 1;
  });
  const auto first = tagged(1, 8);
  bus_.publish_raw("A", first.data(), first.size());
  scheduler_.run_until(0);
  EXPECT_EQ(tags, (std::vector<int>{1, 4, 5, 6, 13, 14, 15}));
  EXPECT_EQ(corrupted, 0);
}

TEST_F(VirtualBusTest, AHandlerThatThrowsLeavesTheOtherDeliveriesInOrder) {
  std::vector<int> tags;
  bus_.subscribe_raw("A", [&](const std::string&, const uint8_t* data, std::size_t, int64_t) {
    tags.push_back(data[0]);
    if (data[0] == 2) throw std::runtime_error("handler fails");
  });
  for (uint8_t i = 1; i <= 4; ++i) {
    const auto bytes = tagged(i, 16);
    bus_.publish_raw("A", bytes.data(), bytes.size());
  }
  EXPECT_THROW(scheduler_.run_until(0), std::runtime_error);
  scheduler_.run_until(0);
  const auto fifth = tagged(5, 16);
  bus_.publish_raw("A", fifth.data(), fifth.size());
  scheduler_.run_until(0);
  EXPECT_EQ(tags, (std::vector<int>{1, 2, 3, 4, 5}));
}

// One event hands a message to all its subscribers: what a handler publishes or schedules at
// that time comes after the message's last delivery, and a stop it requests leaves the other
// subscribers served.
TEST_F(VirtualBusTest, AMessageIsOneEventForAllItsSubscribers) {
  std::vector<std::string> order;
  bus_.subscribe_raw("A", [&](const std::string&, const uint8_t* data, std::size_t, int64_t) {
    order.push_back("first:" + std::to_string(data[0]));
    if (data[0] == 1) {
      const auto reply = tagged(2, 4);
      bus_.publish_raw("A", reply.data(), reply.size());
      scheduler_.schedule_at(scheduler_.clock().now_us(), [&] { order.push_back("timer"); });
      scheduler_.request_stop();
    }
  });
  bus_.subscribe_raw("A", [&](const std::string&, const uint8_t* data, std::size_t, int64_t) {
    order.push_back("second:" + std::to_string(data[0]));
  });
  const auto bytes = tagged(1, 4);
  bus_.publish_raw("A", bytes.data(), bytes.size());
  EXPECT_EQ(scheduler_.pending(), 1u);
  EXPECT_EQ(scheduler_.run_until(0), 1u) << "the stop ends the run after the message's event";
  EXPECT_EQ(order, (std::vector<std::string>{"first:1", "second:1"}));
  scheduler_.run_until(0);
  EXPECT_EQ(order, (std::vector<std::string>{"first:1", "second:1", "first:2", "second:2", "timer"}));
}

// A subscriber that throws does not keep the message from the ones after it; the exception
// leaves the event once they all had it.
TEST_F(VirtualBusTest, AThrowingSubscriberLeavesTheMessageToTheOthers) {
  std::vector<std::string> got;
  bus_.subscribe_raw("A", [&](const std::string&, const uint8_t* data, std::size_t, int64_t) {
    got.push_back("x" + std::to_string(data[0]));
    throw std::runtime_error("x fails");
  });
  bus_.subscribe_raw("A", [&](const std::string&, const uint8_t* data, std::size_t, int64_t) {
    got.push_back("y" + std::to_string(data[0]));
    throw std::logic_error("y fails too");
  });
  bus_.subscribe_raw("A", [&](const std::string&, const uint8_t* data, std::size_t, int64_t) {
    got.push_back("z" + std::to_string(data[0]));
  });
  for (uint8_t i = 1; i <= 2; ++i) {
    const auto bytes = tagged(i, 4);
    bus_.publish_raw("A", bytes.data(), bytes.size());
  }
  EXPECT_THROW(scheduler_.run_until(0), std::runtime_error) << "the first exception, not the second";
  EXPECT_EQ(got, (std::vector<std::string>{"x1", "y1", "z1"}));
  EXPECT_THROW(scheduler_.run_until(0), std::runtime_error);
  EXPECT_EQ(got, (std::vector<std::string>{"x1", "y1", "z1", "x2", "y2", "z2"}));
  EXPECT_EQ(scheduler_.pending(), 0u);
}

// The bus's events hold only a pointer to it: going away, it cancels them, so the scheduler
// neither runs them nor holds anything of the bus afterwards.
TEST_F(VirtualBusTest, ABusDestroyedWithDeliveriesPendingCancelsThem) {
  int delivered = 0, later = 0;
  {
    VirtualBus doomed(scheduler_);
    doomed.subscribe_raw("A", [&](const std::string&, const uint8_t*, std::size_t, int64_t) { ++delivered; });
    doomed.subscribe_raw("A", [&](const std::string&, const uint8_t*, std::size_t, int64_t) { ++delivered; });
    const auto bytes = tagged(1, 16);
    for (int i = 0; i < 3; ++i) doomed.publish_raw("A", bytes.data(), bytes.size());
    scheduler_.schedule_at(0, [&] { ++later; });
    EXPECT_EQ(scheduler_.pending(), 4u) << "one event per message, whatever its subscribers";
  }
  EXPECT_EQ(scheduler_.pending(), 1u);
  scheduler_.run_until(10);
  EXPECT_EQ(delivered, 0);
  EXPECT_EQ(later, 1);
}

}  // namespace
}  // namespace a3::common
