// From a scenario and the run's options to the configuration of every node of the rig: the
// dynamics (airframe with the scenario's payloads, wind, the start on the ground below the
// initial pose), the bridge and the flight controller (the same airframe, the scenario's
// geofence and altitude envelope), the link emulator (initial slice, degradations, trace),
// the tool server and airspace monitor (airspace, sensors, payloads, energy numbers), and the
// conversation (mission, agent's briefing).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "agent/conversation/agent.hpp"
#include "agent/conversation/conversation_node.hpp"
#include "common/channel.hpp"
#include "rigs/run/run_options.hpp"
#include "rigs/run/vehicle_unit.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

struct RigConfigs {
  std::vector<VehicleConfigs> vehicles;  // vehicle 0 first: the one the agent under test flies
  agent::ConversationConfig conversation;

  const VehicleConfigs& agent_vehicle() const { return vehicles.front(); }
};

// Throws common::InputError / std::invalid_argument naming what is wrong.
RigConfigs make_rig_configs(const Scenario& scenario, const RunOptions& options);
// One vehicle of the scenario, on vehicle `id`'s channels. Throws as make_rig_configs does.
VehicleConfigs make_vehicle_configs(const Scenario& scenario, const RunOptions& options, common::VehicleId id);

// The agent named by options.agent, with options.think_time added. Throws naming the problem.
std::unique_ptr<agent::Agent> make_agent(const RunOptions& options);

}  // namespace a3::rigs
