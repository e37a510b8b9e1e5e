// The nodes of one rig, built from its configuration: all of them (one process), or one part
// of them (`a3rig run --processes` runs each part as a process of its own: the ground side —
// recorder, LCM log, conversation — stays in `a3rig run`, every other part is an
// `a3rig node part NAME` child).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "agent/conversation/conversation_node.hpp"
#include "agent/vehicle/airspace_monitor_node.hpp"
#include "agent/vehicle/tool_server_node.hpp"
#include "bridge/can/can_bus.hpp"
#include "bridge/nodes/bridge_node.hpp"
#include "bridge/nodes/fc_node.hpp"
#include "common/node.hpp"
#include "dynamics/dynamics_node.hpp"
#include "linkemu/link_emulator_node.hpp"
#include "rigs/core/episode_recorder.hpp"
#include "rigs/core/lcm_log_node.hpp"
#include "rigs/core/node_configs.hpp"
#include "rigs/core/run_options.hpp"
#include "rigs/core/scenario.hpp"

namespace a3::rigs {

// The parts a rig is made of, as `a3rig node part` names them.
enum class RigPart { kGround, kDynamics, kBridge, kFc, kLinkemu, kVehicle };
const std::vector<RigPart>& rig_parts_outside_ground();  // dynamics, bridge, fc, linkemu, vehicle
std::vector<RigPart> all_rig_parts();                     // the ground first, then those
std::string to_string(RigPart part);
RigPart parse_rig_part(const std::string& name);  // throws std::invalid_argument listing the names

struct RigNodes {
  // Ground: the recorder, the LCM log (when asked for), the conversation with its agent.
  std::unique_ptr<EpisodeRecorderNode> recorder;
  std::unique_ptr<LcmLogNode> log;
  std::unique_ptr<agent::ConversationNode> conversation;
  std::unique_ptr<dynamics::DynamicsNode> dynamics;
  std::unique_ptr<bridge::BridgeNode> bridge;
  std::unique_ptr<bridge::FcNode> fc;
  std::unique_ptr<linkemu::LinkEmulatorNode> link;
  // Vehicle: the tool server (MCP/A2A on the vehicle side, safety gate, peers) and the
  // airspace monitor.
  std::unique_ptr<agent::ToolServerNode> tools;
  std::unique_ptr<agent::AirspaceMonitorNode> monitor;

  // The nodes built, recorders first, the conversation last.
  std::vector<common::Node*> in_start_order() const;
  // Counters of the nodes built, {node name: counters} as node_stats_json gives them (a part
  // in another process has none here: its counters come over the bus).
  nlohmann::json counters() const;
};

struct RigNodeBuses {
  bridge::CanBus* can_bridge = nullptr;  // needed for kBridge
  bridge::CanBus* can_fc = nullptr;      // needed for kFc
};

// Builds the nodes of the given parts. Throws naming the problem.
RigNodes make_rig_nodes(const std::vector<RigPart>& parts, const RigConfigs& configs, const RunOptions& options,
                        const Scenario& scenario, const RigNodeBuses& buses, bool agent_in_thread);

}  // namespace a3::rigs
