// One vehicle as a unit the rig builds N times: its physics (dynamics), the simulator's devices
// on its CAN bus (bridge), its flight controller on the same bus (fc), its end of the emulated
// link (linkemu) and what runs on board (vehicle: tool server and airspace monitor). Every node
// of a unit talks on its vehicle's channels (common/channels.hpp: vehicle n's are A3_V<n>_...)
// and its own CAN bus, so two units in one rig do not mix. Today's rig is one unit, vehicle 0.
#pragma once

#include <memory>
#include <vector>

#include "bridge/can/can_bus.hpp"
#include "bridge/nodes/fc_node.hpp"
#include "bridge/sim/bridge_node.hpp"
#include "common/channel.hpp"
#include "common/node.hpp"
#include "dynamics/dynamics_node.hpp"
#include "linkemu/link_emulator_config.hpp"
#include "linkemu/link_emulator_node.hpp"
#include "rigs/run/rig_part.hpp"
#include "vehicle/airspace_monitor_node.hpp"
#include "vehicle/tool_server_config.hpp"
#include "vehicle/tool_server_node.hpp"

namespace a3::rigs {

struct VehicleConfigs {
  dynamics::DynamicsNodeConfig dynamics;
  bridge::BridgeNodeConfig bridge;
  bridge::FcNodeConfig fc;
  linkemu::LinkEmulatorConfig link;
  vehicle::ToolServerConfig tool_server;
  vehicle::AirspaceMonitorConfig monitor;

  // Puts every node of the unit on vehicle `id`'s channels.
  void assign_vehicle(common::VehicleId id);
  common::VehicleId vehicle_id() const { return dynamics.vehicle; }
};

// The unit's CAN bus as its bridge and its fc attach to it (each needed only for its part).
struct VehicleBuses {
  bridge::CanBus* can_bridge = nullptr;
  bridge::CanBus* can_fc = nullptr;
};

struct VehicleNodes {
  std::unique_ptr<dynamics::DynamicsNode> dynamics;
  std::unique_ptr<bridge::BridgeNode> bridge;
  std::unique_ptr<bridge::FcNode> fc;
  std::unique_ptr<linkemu::LinkEmulatorNode> link;
  std::unique_ptr<vehicle::ToolServerNode> tools;
  std::unique_ptr<vehicle::AirspaceMonitorNode> monitor;

  // The nodes built: dynamics, bridge, fc, link, tool server, monitor.
  std::vector<common::Node*> in_start_order() const;
};

// Builds the unit's nodes of the given parts (kGround is not a vehicle's and is ignored).
// Throws std::logic_error when the bridge or fc is asked for without its CAN bus.
VehicleNodes make_vehicle(const std::vector<RigPart>& parts, const VehicleConfigs& configs, const VehicleBuses& buses);

}  // namespace a3::rigs
