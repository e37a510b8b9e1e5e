// In-process bus delivering through the scheduler.
#include "common/virtual_bus.hpp"

#include <memory>
#include <vector>

namespace a3::common {

bool VirtualBus::publish_raw(const std::string& channel, const uint8_t* data, std::size_t size) {
  ++published_;
  std::shared_ptr<const std::vector<uint8_t>> bytes;
  for (const auto& [id, sub] : subscribers_) {
    if (sub.channel != channel) continue;
    if (!bytes) bytes = std::make_shared<const std::vector<uint8_t>>(data, data + size);
    std::weak_ptr<RawHandler> weak = sub.handler;
    executor_.schedule_at(executor_.clock().now_us(), [this, weak, channel, bytes] {
      if (auto handler = weak.lock()) {
        (*handler)(channel, bytes->data(), bytes->size(), executor_.clock().now_us());
      }
    });
  }
  return true;
}

SubscriptionId VirtualBus::subscribe_raw(const std::string& channel, RawHandler handler) {
  const SubscriptionId id = next_id_++;
  subscribers_.emplace(id, Subscriber{channel, std::make_shared<RawHandler>(std::move(handler))});
  return id;
}

void VirtualBus::unsubscribe(SubscriptionId id) { subscribers_.erase(id); }

}  // namespace a3::common
