// A node's declared channels, enforced.
#include "common/port_checked_bus.hpp"

#include <stdexcept>

namespace a3::common {

bool PortCheckedBus::publish_raw(const std::string& channel, const uint8_t* data, std::size_t size) {
  if (!ports_.publishes_on(channel)) {
    throw std::logic_error("node " + node_ + " published on " + channel + ", which its ports() do not declare");
  }
  return inner_.publish_raw(channel, data, size);
}

SubscriptionId PortCheckedBus::subscribe_raw(const std::string& channel, RawHandler handler) {
  if (!ports_.subscribes_to(channel)) {
    throw std::logic_error("node " + node_ + " subscribed to " + channel + ", which its ports() do not declare");
  }
  return inner_.subscribe_raw(channel, std::move(handler));
}

Bus& bus_for_node(Node& node, Bus& bus, std::unique_ptr<Bus>& holder) {
  std::optional<NodePorts> ports = node.ports();
  if (!ports) return bus;
  holder = std::make_unique<PortCheckedBus>(bus, node.name(), std::move(*ports));
  return *holder;
}

}  // namespace a3::common
