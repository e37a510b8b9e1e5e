// The channels a node publishes and subscribes, declared by the node (PX4 modules name their
// topics; here the runtime holds a node to its declaration: PortCheckedBus) and drawn by
// `a3rig topology`. Built with the typed channels, so each port carries its message type.
#pragma once

#include <string>
#include <vector>

#include "common/channel.hpp"

namespace a3::common {

// "a3lcm.vehicle_state_t": the package and name of an lcm-gen type (lcm-spy's spelling).
template <typename Msg>
std::string message_type_name() {
  return std::string("a3lcm.") + Msg::getTypeName();
}

struct Port {
  // kListen: a subscription that may have no publisher in the rig (a service for clients from
  // outside, or statistics only real time publishes); kSubscribe needs one (`a3rig topology`).
  enum class Direction { kPublish, kSubscribe, kListen };
  std::string channel;       // the name on the bus, vehicle scope resolved
  std::string message_type;  // the lcm-gen type name, e.g. "a3lcm.vehicle_state_t"
  Direction direction = Direction::kPublish;
};

class NodePorts {
 public:
  template <typename Msg>
  NodePorts& publishes(const TypedChannel<Msg>& channel) {
    return add(channel.name, message_type_name<Msg>(), Port::Direction::kPublish);
  }
  template <typename Msg>
  NodePorts& publishes(const RigChannel<Msg>& channel) {
    return publishes(TypedChannel<Msg>(channel));
  }
  template <typename Msg>
  NodePorts& subscribes(const TypedChannel<Msg>& channel) {
    return add(channel.name, message_type_name<Msg>(), Port::Direction::kSubscribe);
  }
  template <typename Msg>
  NodePorts& subscribes(const RigChannel<Msg>& channel) {
    return subscribes(TypedChannel<Msg>(channel));
  }
  template <typename Msg>
  NodePorts& listens(const TypedChannel<Msg>& channel) {
    return add(channel.name, message_type_name<Msg>(), Port::Direction::kListen);
  }
  template <typename Msg>
  NodePorts& listens(const RigChannel<Msg>& channel) {
    return listens(TypedChannel<Msg>(channel));
  }

  // A port by name and type name (a node that logs every declared channel, for one).
  NodePorts& declare(const std::string& channel, const std::string& type, Port::Direction direction) {
    return add(channel, type, direction);
  }

  const std::vector<Port>& ports() const { return ports_; }
  bool publishes_on(const std::string& channel) const { return has(channel, Port::Direction::kPublish); }
  bool subscribes_to(const std::string& channel) const {
    return has(channel, Port::Direction::kSubscribe) || has(channel, Port::Direction::kListen);
  }

 private:
  NodePorts& add(const std::string& channel, const std::string& type, Port::Direction direction);
  bool has(const std::string& channel, Port::Direction direction) const;

  std::vector<Port> ports_;
};

}  // namespace a3::common
