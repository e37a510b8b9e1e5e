// The rig's graph of nodes and channels, from the ports every node declares (common/node_ports):
// who publishes and who subscribes each channel, with its message type. In real time the
// runtimes add what they publish themselves (node statistics; in lockstep the pacer's grants
// and the followers' answers). `a3rig topology` prints it as text or Graphviz dot, and
// problems() says what would break: a subscription nobody publishes, or one channel carrying
// two message types.
#pragma once

#include <string>
#include <vector>

#include "common/node_ports.hpp"
#include "rigs/run/rig_nodes.hpp"
#include "rigs/run/run_options.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

struct TopologyNode {
  std::string name;
  common::NodePorts ports;
};

struct RigTopology {
  std::vector<TopologyNode> nodes;
};

// From built (not started) nodes; a node without declared ports is a problem of its own.
RigTopology rig_topology(const RigNodes& nodes, const RunOptions& options);
// The rig `a3rig run` would build for the scenario with these options (nodes built on a CAN bus
// of no consequence, never started; the LCM log left out: it subscribes every channel).
RigTopology rig_topology(const Scenario& scenario, RunOptions options);

// One line each; empty when the graph is whole.
std::vector<std::string> topology_problems(const RigTopology& topology);

// By channel: "A3_STATE  a3lcm.vehicle_state_t  dynamics -> bridge, tool_server, ...".
std::string topology_text(const RigTopology& topology);
// Nodes as boxes, channels as ellipses labelled with their type; optional inputs dashed.
std::string topology_dot(const RigTopology& topology);

}  // namespace a3::rigs
