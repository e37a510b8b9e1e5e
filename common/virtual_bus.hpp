// In-process bus for the virtual-time runtime: a publication is one scheduler event at the
// current virtual time (after the events already due then), which hands a copy of the
// LCM-encoded bytes to each of the channel's subscribers of that moment, in subscription order.
// Deterministic FIFO per channel. A handler's own publications and timers come after the
// message's last delivery, as they would with an event per delivery; a stop requested by a
// handler takes effect after it. A handler that throws does not keep the message from the
// others: its exception leaves the event after the message's last delivery.
// Allocation-free in steady state: copies go to reused message buffers, messages wait in a
// reused ring in the order their events run, and each event's callback holds only `this`.
// The ring relies on every delivery event being scheduled at the executor's current time
// (so they run in the order scheduled) and on nothing but the bus's destructor cancelling
// one (unsubscribe leaves the event, which then delivers nothing to that subscriber).
// The executor must outlive the bus (the bus cancels its pending deliveries when it goes).
// Subscribers are found by index (ids are handed out in order); a handler unsubscribed while
// a delivery runs is kept until the delivery ends, as it may be the one running.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/bus.hpp"
#include "common/executor.hpp"

namespace a3::common {

class VirtualBus final : public Bus {
 public:
  explicit VirtualBus(Executor& executor) : executor_(executor) {}
  ~VirtualBus() override;
  VirtualBus(const VirtualBus&) = delete;
  VirtualBus& operator=(const VirtualBus&) = delete;

  bool publish_raw(const std::string& channel, const uint8_t* data, std::size_t size) override;
  SubscriptionId subscribe_raw(const std::string& channel, RawHandler handler) override;
  void unsubscribe(SubscriptionId id) override;

  uint64_t messages_published() const { return published_; }

 private:
  struct Subscriber {
    std::string channel;
    std::unique_ptr<RawHandler> handler;  // null once unsubscribed
  };
  struct Message {
    std::string channel;
    std::vector<uint8_t> bytes;
    std::vector<SubscriptionId> recipients;  // the channel's subscribers when it was published
  };
  struct Delivery {
    uint32_t message;  // index into messages_
    TimerId event;
  };

  uint32_t store_message(const std::string& channel, const uint8_t* data, std::size_t size,
                         const std::vector<SubscriptionId>& recipients);
  void deliver_next();
  void hand_to_subscriber(SubscriptionId subscriber, const Message& message);
  void push_delivery(const Delivery& delivery);
  Delivery pop_delivery();

  Executor& executor_;
  std::vector<Subscriber> subscribers_;  // subscription id - 1
  int delivering_ = 0;                    // handlers running now
  std::vector<std::unique_ptr<RawHandler>> retired_;  // unsubscribed while delivering_ > 0
  // Each channel's subscribers in subscription order: the order a message is delivered in.
  std::unordered_map<std::string, std::vector<SubscriptionId>> by_channel_;
  SubscriptionId next_id_ = 1;
  uint64_t published_ = 0;
  std::vector<std::unique_ptr<Message>> messages_;  // stable addresses while handlers run
  std::vector<uint32_t> free_messages_;
  std::vector<Delivery> ring_;  // pending deliveries, oldest at ring_head_
  std::size_t ring_head_ = 0;
  std::size_t ring_count_ = 0;
};

}  // namespace a3::common
