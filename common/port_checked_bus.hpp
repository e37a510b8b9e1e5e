// The bus as one node sees it: every publication and subscription must be on a channel the node
// declared in its ports() (node_ports.hpp), else std::logic_error naming the node and the
// channel, so a declaration cannot drift from the code (the virtual-time tests fly every node).
// Everything else passes through to the rig's bus; decode failures are counted there.
#pragma once

#include <memory>
#include <string>

#include "common/bus.hpp"
#include "common/node.hpp"
#include "common/node_ports.hpp"

namespace a3::common {

class PortCheckedBus final : public Bus {
 public:
  PortCheckedBus(Bus& inner, std::string node, NodePorts ports)
      : inner_(inner), node_(std::move(node)), ports_(std::move(ports)) {}

  bool publish_raw(const std::string& channel, const uint8_t* data, std::size_t size) override;
  SubscriptionId subscribe_raw(const std::string& channel, RawHandler handler) override;
  void unsubscribe(SubscriptionId id) override { inner_.unsubscribe(id); }
  Bus& counting_bus() override { return inner_.counting_bus(); }

 private:
  Bus& inner_;
  std::string node_;
  NodePorts ports_;
};

// The bus to start `node` on: a PortCheckedBus over `bus` when the node declares its ports,
// kept in `holder` (which must outlive the node's activity), else `bus` itself.
Bus& bus_for_node(Node& node, Bus& bus, std::unique_ptr<Bus>& holder);

}  // namespace a3::common
