// A rig node: subscribes and schedules its timers when started; everything it does
// afterwards happens in callbacks run by the executor (PX4's "read inputs, update,
// publish"). The same node object runs unchanged on either runtime.
#pragma once

#include <optional>
#include <string>

#include "common/bus.hpp"
#include "common/counters.hpp"
#include "common/executor.hpp"
#include "common/node_ports.hpp"

namespace a3::common {

class Node {
 public:
  virtual ~Node() = default;
  virtual std::string name() const = 0;
  // Subscribe on `bus`, schedule on `executor`. Both outlive the node's activity.
  virtual void start(Executor& executor, Bus& bus) = 0;
  // What the node counts (published on the bus by the runtime; empty by default).
  virtual const CounterSet& counters() const;
  // The channels the node publishes and subscribes. The runtimes hold a node that declares
  // them to its declaration (a publication or subscription outside it throws: PortCheckedBus);
  // every node of the rig declares them (`a3rig topology` checks), test doubles may not.
  virtual std::optional<NodePorts> ports() const { return std::nullopt; }
};

}  // namespace a3::common
