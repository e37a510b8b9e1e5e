// In-process bus delivering through the scheduler (see virtual_bus.hpp).
#include "common/virtual_bus.hpp"

#include <algorithm>
#include <exception>

namespace a3::common {

VirtualBus::~VirtualBus() {
  while (ring_count_ > 0) executor_.cancel(pop_delivery().event);
}

bool VirtualBus::publish_raw(const std::string& channel, const uint8_t* data, std::size_t size) {
  ++published_;
  const auto it = by_channel_.find(channel);
  if (it == by_channel_.end() || it->second.empty()) return true;
  const uint32_t message = store_message(channel, data, size, it->second);
  // Events at one time run in the order scheduled, so each one delivers the oldest message.
  const TimerId event = executor_.schedule_at(executor_.clock().now_us(), [this] { deliver_next(); });
  push_delivery(Delivery{message, event});
  return true;
}

uint32_t VirtualBus::store_message(const std::string& channel, const uint8_t* data, std::size_t size,
                                   const std::vector<SubscriptionId>& recipients) {
  uint32_t index = 0;
  if (free_messages_.empty()) {
    index = static_cast<uint32_t>(messages_.size());
    messages_.push_back(std::make_unique<Message>());
  } else {
    index = free_messages_.back();
    free_messages_.pop_back();
  }
  Message& message = *messages_[index];
  message.channel = channel;
  message.bytes.assign(data, data + size);
  message.recipients.assign(recipients.begin(), recipients.end());
  return index;
}

void VirtualBus::deliver_next() {
  const Delivery delivery = pop_delivery();
  // Released after the last handler (which may publish): its bytes stay put while they read them.
  const Message& message = *messages_[delivery.message];
  std::exception_ptr failure;
  for (const SubscriptionId subscriber : message.recipients) {
    try {
      hand_to_subscriber(subscriber, message);
    } catch (...) {
      if (!failure) failure = std::current_exception();
    }
  }
  free_messages_.push_back(delivery.message);
  if (failure) std::rethrow_exception(failure);
}

void VirtualBus::hand_to_subscriber(SubscriptionId subscriber, const Message& message) {
  RawHandler* handler = subscribers_[subscriber - 1].handler.get();
  if (handler == nullptr) return;  // unsubscribed while the message was in flight
  struct Delivering {
    VirtualBus& bus;
    explicit Delivering(VirtualBus& b) : bus(b) { ++bus.delivering_; }
    ~Delivering() {
      if (--bus.delivering_ == 0) bus.retired_.clear();
    }
  } delivering(*this);
  (*handler)(message.channel, message.bytes.data(), message.bytes.size(), executor_.clock().now_us());
}

void VirtualBus::push_delivery(const Delivery& delivery) {
  if (ring_count_ == ring_.size()) {
    std::vector<Delivery> bigger(std::max<std::size_t>(16, 2 * ring_.size()));
    for (std::size_t i = 0; i < ring_count_; ++i) bigger[i] = ring_[(ring_head_ + i) % ring_.size()];
    ring_.swap(bigger);
    ring_head_ = 0;
  }
  ring_[(ring_head_ + ring_count_) % ring_.size()] = delivery;
  ++ring_count_;
}

VirtualBus::Delivery VirtualBus::pop_delivery() {
  const Delivery delivery = ring_[ring_head_];
  ring_head_ = (ring_head_ + 1) % ring_.size();
  --ring_count_;
  return delivery;
}

SubscriptionId VirtualBus::subscribe_raw(const std::string& channel, RawHandler handler) {
  const SubscriptionId id = next_id_++;
  subscribers_.push_back(Subscriber{channel, std::make_unique<RawHandler>(std::move(handler))});
  by_channel_[channel].push_back(id);
  return id;
}

void VirtualBus::unsubscribe(SubscriptionId id) {
  if (id == 0 || id > subscribers_.size() || subscribers_[id - 1].handler == nullptr) return;
  Subscriber& subscriber = subscribers_[id - 1];
  std::vector<SubscriptionId>& ids = by_channel_[subscriber.channel];
  ids.erase(std::remove(ids.begin(), ids.end(), id), ids.end());
  // The handler may be the one running (it unsubscribed itself): keep it until that ends.
  if (delivering_ > 0) retired_.push_back(std::move(subscriber.handler));
  subscriber.handler.reset();
}

}  // namespace a3::common
