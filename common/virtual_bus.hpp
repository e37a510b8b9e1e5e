// In-process bus for the virtual-time runtime: a publication is delivered to each
// subscriber as a scheduler event at the current virtual time (after the events already
// due then), carrying a copy of the LCM-encoded bytes. Deterministic FIFO per channel.
#pragma once

#include <map>
#include <string>
#include <unordered_map>

#include "common/bus.hpp"
#include "common/executor.hpp"

namespace a3::common {

class VirtualBus final : public Bus {
 public:
  explicit VirtualBus(Executor& executor) : executor_(executor) {}

  bool publish_raw(const std::string& channel, const uint8_t* data, std::size_t size) override;
  SubscriptionId subscribe_raw(const std::string& channel, RawHandler handler) override;
  void unsubscribe(SubscriptionId id) override;

  uint64_t messages_published() const { return published_; }

 private:
  struct Subscriber {
    std::string channel;
    std::shared_ptr<RawHandler> handler;
  };
  Executor& executor_;
  std::map<SubscriptionId, Subscriber> subscribers_;  // ordered: delivery order is stable
  SubscriptionId next_id_ = 1;
  uint64_t published_ = 0;
};

}  // namespace a3::common
