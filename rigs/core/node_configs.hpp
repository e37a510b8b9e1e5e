// From a scenario and the run's options to the configuration of every node of the rig: the
// dynamics (airframe with the scenario's payloads, wind, the start on the ground below the
// initial pose), the bridge and the flight controller (the same airframe, the scenario's
// geofence and altitude envelope), the link emulator (initial slice, degradations, trace),
// the tool server and airspace monitor (airspace, sensors, payloads, energy numbers), and the
// conversation (mission, agent's briefing).
#pragma once

#include <memory>
#include <string>

#include "agent/conversation/agent.hpp"
#include "agent/conversation/conversation_node.hpp"
#include "agent/vehicle/airspace_monitor_node.hpp"
#include "agent/vehicle/tool_server_config.hpp"
#include "bridge/nodes/bridge_node.hpp"
#include "bridge/nodes/fc_node.hpp"
#include "dynamics/dynamics_node.hpp"
#include "linkemu/link_emulator_config.hpp"
#include "rigs/core/run_options.hpp"
#include "rigs/core/scenario.hpp"

namespace a3::rigs {

struct RigConfigs {
  dynamics::DynamicsNodeConfig dynamics;
  bridge::BridgeNodeConfig bridge;
  bridge::FcNodeConfig fc;
  linkemu::LinkEmulatorConfig link;
  agent::ToolServerConfig tool_server;
  agent::AirspaceMonitorConfig monitor;
  agent::ConversationConfig conversation;
};

// Throws common::InputError / std::invalid_argument naming what is wrong.
RigConfigs make_rig_configs(const Scenario& scenario, const RunOptions& options);

// The agent named by options.agent, with options.think_time added. Throws naming the problem.
std::unique_ptr<agent::Agent> make_agent(const RunOptions& options);

}  // namespace a3::rigs
