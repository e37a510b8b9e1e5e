// Node ports.
#include "common/node_ports.hpp"

#include <algorithm>

namespace a3::common {

NodePorts& NodePorts::add(const std::string& channel, const std::string& type, Port::Direction direction) {
  if (!has(channel, direction)) ports_.push_back({channel, type, direction});
  return *this;
}

bool NodePorts::has(const std::string& channel, Port::Direction direction) const {
  return std::any_of(ports_.begin(), ports_.end(),
                     [&](const Port& p) { return p.channel == channel && p.direction == direction; });
}

}  // namespace a3::common
