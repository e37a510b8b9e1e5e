// The typed Bus helpers' shared machinery: typed subscribers of one type that receive the
// same bytes share one decode (and still each get the message, and still each count bytes
// that do not decode); typed publish encodes into reused per-thread buffers, also when a
// handler publishes from inside a synchronous delivery. SyncBus (below) delivers inside
// publish_raw, as no production bus does, to reach the nested paths.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "a3lcm/vehicle_state_t.hpp"
#include "common/bus.hpp"
#include "common/virtual_bus.hpp"
#include "common/virtual_scheduler.hpp"
#include "tests/common/bus_test_messages.hpp"

namespace a3::common {
namespace {

// A message type in lcm-gen's shape that counts its decodes: 8 bytes, a magic byte first.
struct CountedMsg {
  static inline int decodes = 0;
  uint8_t magic = 0xC7;
  uint8_t value[7] = {};

  static const char* getTypeName() { return "CountedMsg"; }
  int getEncodedSize() const { return 8; }
  int encode(void* buf, int offset, int maxlen) const {
    if (maxlen < 8) return -1;
    auto* out = static_cast<uint8_t*>(buf) + offset;
    out[0] = magic;
    std::memcpy(out + 1, value, 7);
    return 8;
  }
  int decode(const void* buf, int offset, int maxlen) {
    ++decodes;
    const auto* in = static_cast<const uint8_t*>(buf) + offset;
    if (maxlen != 8 || in[0] != 0xC7) return -1;
    magic = in[0];
    std::memcpy(value, in + 1, 7);
    return 8;
  }
};

CountedMsg counted(uint8_t v) {
  CountedMsg m;
  for (uint8_t& b : m.value) b = v;
  return m;
}

// Delivers synchronously inside publish_raw, to every subscriber of the channel in order.
class SyncBus final : public Bus {
 public:
  bool publish_raw(const std::string& channel, const uint8_t* data, std::size_t size) override {
    const auto handlers = handlers_[channel];  // a copy: handlers may subscribe
    for (const RawHandler& handler : handlers) handler(channel, data, size, 0);
    return true;
  }
  SubscriptionId subscribe_raw(const std::string& channel, RawHandler handler) override {
    handlers_[channel].push_back(std::move(handler));
    return ++next_id_;
  }
  void unsubscribe(SubscriptionId) override {}

 private:
  std::map<std::string, std::vector<RawHandler>> handlers_;
  SubscriptionId next_id_ = 0;
};

TEST(TypedBus, SubscribersOfOneTypeShareOneDecodeOfTheSameBytes) {
  VirtualScheduler scheduler;
  VirtualBus bus(scheduler);
  std::vector<std::vector<int>> seen(3);
  for (auto& values : seen) {
    bus.subscribe<CountedMsg>("C", [&values](const CountedMsg& m, int64_t) { values.push_back(m.value[6]); });
  }
  CountedMsg::decodes = 0;
  bus.publish("C", counted(1));
  bus.publish("C", counted(2));
  bus.publish("C", counted(2));  // the same bytes again: still no new decode
  bus.publish("C", counted(1));
  scheduler.run_until(0);
  for (const auto& values : seen) EXPECT_EQ(values, (std::vector<int>{1, 2, 2, 1}));
  EXPECT_EQ(CountedMsg::decodes, 3);
  EXPECT_EQ(bus.decode_failures(), 0u);
}

TEST(TypedBus, EverySubscriberGetsTheMessageItsBytesEncode) {
  VirtualScheduler scheduler;
  VirtualBus bus(scheduler);
  std::vector<std::vector<uint8_t>> received[2];
  for (auto& list : received) {
    bus.subscribe<a3lcm::vehicle_state_t>("S", [&list](const a3lcm::vehicle_state_t& m, int64_t) {
      list.push_back(test::encode_bytes(m));
    });
  }
  std::vector<std::vector<uint8_t>> sent;
  for (int64_t t : {1, 2, 2, 3}) {
    const a3lcm::vehicle_state_t state = test::make_state(t);
    sent.push_back(test::encode_bytes(state));
    bus.publish("S", state);
  }
  scheduler.run_until(0);
  EXPECT_EQ(received[0], sent);
  EXPECT_EQ(received[1], sent);
}

TEST(TypedBus, BytesThatDoNotDecodeAreCountedForEverySubscriberEvenAfterAGoodCopy) {
  VirtualScheduler scheduler;
  VirtualBus bus(scheduler);
  int delivered = 0;
  for (int i = 0; i < 3; ++i) {
    bus.subscribe<a3lcm::vehicle_state_t>("S", [&delivered](const a3lcm::vehicle_state_t&, int64_t) { ++delivered; });
  }
  const std::vector<uint8_t> good = test::encode_bytes(test::make_state(7));
  // A prefix of the good bytes: must not be taken for the message decoded just before.
  const std::vector<uint8_t> truncated(good.begin(), good.end() - 1);
  std::vector<uint8_t> corrupt = good;
  corrupt[0] ^= 0xFF;  // the fingerprint
  bus.publish_raw("S", good.data(), good.size());
  bus.publish_raw("S", truncated.data(), truncated.size());
  bus.publish_raw("S", corrupt.data(), corrupt.size());
  bus.publish_raw("S", good.data(), good.size());
  scheduler.run_until(0);
  EXPECT_EQ(delivered, 6);
  EXPECT_EQ(bus.decode_failures(), 6u);
}

TEST(TypedBus, ANestedDeliveryOfTheSameTypeLeavesTheOuterHandlersMessageAlone) {
  SyncBus bus;
  std::vector<int64_t> inner_times;
  int64_t outer_before = 0, outer_after = 0;
  bus.subscribe<a3lcm::vehicle_state_t>("INNER", [&](const a3lcm::vehicle_state_t& m, int64_t) {
    inner_times.push_back(m.utime_us);
  });
  bus.subscribe<a3lcm::vehicle_state_t>("OUTER", [&](const a3lcm::vehicle_state_t& m, int64_t) {
    outer_before = m.utime_us;
    bus.publish("INNER", test::make_state(222));
    outer_after = m.utime_us;
  });
  bus.publish("OUTER", test::make_state(111));
  bus.publish("INNER", test::make_state(333));
  EXPECT_EQ(outer_before, 111);
  EXPECT_EQ(outer_after, 111);
  EXPECT_EQ(inner_times, (std::vector<int64_t>{222, 333}));
}

TEST(TypedBus, APublishFromInsideADeliveryLeavesTheOuterPublishersBytesAlone) {
  SyncBus bus;
  const std::vector<uint8_t> outer = test::encode_bytes(test::make_state(1));
  std::vector<std::vector<uint8_t>> seen_by_second;
  std::vector<std::vector<uint8_t>> inner_seen;
  // The first subscriber publishes another message while the outer bytes are being delivered;
  // the second subscriber must still see the outer bytes.
  bus.subscribe_raw("A", [&](const std::string&, const uint8_t*, std::size_t, int64_t) {
    bus.publish("B", test::make_state(2));
  });
  bus.subscribe_raw("A", [&](const std::string&, const uint8_t* data, std::size_t size, int64_t) {
    seen_by_second.emplace_back(data, data + size);
  });
  bus.subscribe_raw("B", [&](const std::string&, const uint8_t* data, std::size_t size, int64_t) {
    inner_seen.emplace_back(data, data + size);
  });
  bus.publish("A", test::make_state(1));
  ASSERT_EQ(seen_by_second.size(), 1u);
  EXPECT_EQ(seen_by_second[0], outer);
  ASSERT_EQ(inner_seen.size(), 1u);
  EXPECT_EQ(inner_seen[0], test::encode_bytes(test::make_state(2)));
}

}  // namespace
}  // namespace a3::common
