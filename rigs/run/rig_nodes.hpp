// The nodes of one rig, built from its configuration: the ground side (recorder, LCM log,
// conversation) and each vehicle as a unit (vehicle_unit.hpp), all of them (one process) or one
// part of them (`a3rig run --processes` runs each part as a process of its own: the ground side
// stays in `a3rig run`, every other part is an `a3rig node part NAME` child).
#pragma once

#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "agent/conversation/conversation_node.hpp"
#include "common/node.hpp"
#include "rigs/run/episode_recorder.hpp"
#include "rigs/run/lcm_log_node.hpp"
#include "rigs/run/node_configs.hpp"
#include "rigs/run/rig_part.hpp"
#include "rigs/run/run_options.hpp"
#include "rigs/run/vehicle_unit.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

struct RigNodes {
  // Ground: the recorder, the LCM log (when asked for), the conversation with its agent.
  std::unique_ptr<EpisodeRecorderNode> recorder;
  std::unique_ptr<LcmLogNode> log;
  std::unique_ptr<agent::ConversationNode> conversation;
  // One unit per vehicle, vehicle 0 (the agent's) first.
  std::vector<VehicleNodes> vehicles;

  VehicleNodes& agent_vehicle() { return vehicles.front(); }
  const VehicleNodes& agent_vehicle() const { return vehicles.front(); }
  // The nodes built, recorders first, then each vehicle's, the conversation last.
  std::vector<common::Node*> in_start_order() const;
  // Counters of the nodes built, {node name: counters} as node_stats_json gives them (a part
  // in another process has none here: its counters come over the bus).
  nlohmann::json counters() const;
};

// Builds the nodes of the given parts, every vehicle's with its buses (one entry per vehicle of
// configs; a part without CAN needs none). Throws naming the problem.
RigNodes make_rig_nodes(const std::vector<RigPart>& parts, const RigConfigs& configs, const RunOptions& options,
                        const Scenario& scenario, const std::vector<VehicleBuses>& buses, bool agent_in_thread);

}  // namespace a3::rigs
