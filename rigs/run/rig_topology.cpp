// The rig's graph.
#include "rigs/run/rig_topology.hpp"

#include <map>
#include <set>

#include "bridge/can/virtual_can_bus.hpp"
#include "common/channels.hpp"
#include "common/virtual_scheduler.hpp"
#include "rigs/run/node_configs.hpp"

namespace a3::rigs {
namespace {

using Direction = common::Port::Direction;

struct ChannelUse {
  std::set<std::string> types;
  std::vector<std::string> publishers, subscribers, listeners;
};

std::map<std::string, ChannelUse> uses_by_channel(const RigTopology& t) {
  std::map<std::string, ChannelUse> uses;
  for (const TopologyNode& node : t.nodes) {
    for (const common::Port& p : node.ports.ports()) {
      ChannelUse& use = uses[p.channel];
      use.types.insert(p.message_type);
      auto& list = p.direction == Direction::kPublish     ? use.publishers
                   : p.direction == Direction::kSubscribe ? use.subscribers
                                                          : use.listeners;
      list.push_back(node.name);
    }
  }
  return uses;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "-" : out;
}

// What the runtimes of a real-time run publish and subscribe themselves.
void add_runtime_nodes(RigTopology& t, const RunOptions& o, common::VehicleId vehicle) {
  if (o.runtime != Runtime::kReal) return;
  namespace ch = common::channels;
  common::NodePorts runtime;
  runtime.publishes(ch::kNodeStats);
  if (o.sync == Sync::kLockstep) {
    runtime.listens(ch::kClock).publishes(ch::kClockAck);
    common::NodePorts pacer;
    pacer.publishes(ch::kClock).subscribes(ch::kClockAck).subscribes(ch::kActuators.of(vehicle));
    t.nodes.push_back({"(lockstep pacer)", pacer});
  }
  t.nodes.push_back({"(every node's runtime)", runtime});
}

std::string dot_escaped(const std::string& text) {
  std::string out;
  for (const char c : text) out += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return out;
}

std::string dot_id(const std::string& text) { return "\"" + dot_escaped(text) + "\""; }

}  // namespace

RigTopology rig_topology(const RigNodes& nodes, const RunOptions& o) {
  RigTopology t;
  for (const common::Node* node : nodes.in_start_order()) {
    const auto ports = node->ports();
    t.nodes.push_back({node->name(), ports ? *ports : common::NodePorts()});
    if (!ports) t.nodes.back().name += " (ports not declared)";
  }
  add_runtime_nodes(t, o, 0);
  return t;
}

RigTopology rig_topology(const Scenario& scenario, RunOptions options) {
  options.write_lcm_log = false;
  const RigConfigs configs = make_rig_configs(scenario, options);
  common::VirtualScheduler scheduler;
  bridge::VirtualCanBus can(scheduler);
  auto can_bridge = can.attach("bridge");
  auto can_fc = can.attach("fc");
  const RigNodes nodes =
      make_rig_nodes(all_rig_parts(), configs, options, scenario, {{can_bridge.get(), can_fc.get()}}, false);
  return rig_topology(nodes, options);
}

std::vector<std::string> topology_problems(const RigTopology& t) {
  std::vector<std::string> problems;
  for (const TopologyNode& node : t.nodes) {
    if (node.name.find("(ports not declared)") != std::string::npos) {
      problems.push_back("node " + node.name + ": it does not say what it publishes and subscribes");
    }
  }
  for (const auto& [channel, use] : uses_by_channel(t)) {
    if (use.types.size() > 1) {
      std::string types;
      for (const std::string& type : use.types) types += (types.empty() ? "" : ", ") + type;
      problems.push_back(channel + ": carries more than one message type (" + types + ")");
    }
    if (use.publishers.empty() && !use.subscribers.empty()) {
      problems.push_back(channel + ": " + joined(use.subscribers) + " subscribe" +
                         (use.subscribers.size() == 1 ? "s" : "") + " but no node publishes it");
    }
  }
  return problems;
}

std::string topology_text(const RigTopology& t) {
  std::string out;
  for (const auto& [channel, use] : uses_by_channel(t)) {
    out += channel + "  " + *use.types.begin() + "\n    published by  " + joined(use.publishers) +
           "\n    subscribed by " + joined(use.subscribers) + "\n";
    if (!use.listeners.empty()) out += "    listened by   " + joined(use.listeners) + " (may have no publisher)\n";
  }
  return out;
}

std::string topology_dot(const RigTopology& t) {
  std::string out = "digraph a3rig {\n  rankdir=LR;\n  node [fontname=\"Helvetica\"];\n";
  for (const auto& [channel, use] : uses_by_channel(t)) {
    out += "  " + dot_id(channel) + " [shape=ellipse, label=\"" + dot_escaped(channel) + "\\n" +
           dot_escaped(*use.types.begin()) + "\"];\n";
  }
  for (const TopologyNode& node : t.nodes) {
    out += "  " + dot_id(node.name) + " [shape=box];\n";
    for (const common::Port& p : node.ports.ports()) {
      if (p.direction == Direction::kPublish) {
        out += "  " + dot_id(node.name) + " -> " + dot_id(p.channel) + ";\n";
      } else {
        out += "  " + dot_id(p.channel) + " -> " + dot_id(node.name) +
               (p.direction == Direction::kListen ? " [style=dashed]" : "") + ";\n";
      }
    }
  }
  return out + "}\n";
}

}  // namespace a3::rigs
