// Building one vehicle.
#include "rigs/run/vehicle_unit.hpp"

#include <initializer_list>
#include <stdexcept>

namespace a3::rigs {

// The fc speaks only DroneCAN, on the unit's own bus: it has no channels to assign.
void VehicleConfigs::assign_vehicle(common::VehicleId id) {
  dynamics.vehicle = id;
  bridge.vehicle = id;
  link.channels = linkemu::LinkChannels::of_vehicle(id);
  tool_server.vehicle = id;
  monitor.vehicle = id;
}

std::vector<common::Node*> VehicleNodes::in_start_order() const {
  std::vector<common::Node*> out;
  for (common::Node* n : std::initializer_list<common::Node*>{dynamics.get(), bridge.get(), fc.get(), link.get(),
                                                             tools.get(), monitor.get()}) {
    if (n != nullptr) out.push_back(n);
  }
  return out;
}

VehicleNodes make_vehicle(const std::vector<RigPart>& parts, const VehicleConfigs& c, const VehicleBuses& buses) {
  VehicleNodes n;
  if (has_part(parts, RigPart::kDynamics)) n.dynamics = std::make_unique<dynamics::DynamicsNode>(c.dynamics);
  if (has_part(parts, RigPart::kBridge)) {
    if (buses.can_bridge == nullptr) throw std::logic_error("make_vehicle: the bridge needs a CAN bus");
    n.bridge = std::make_unique<bridge::BridgeNode>(*buses.can_bridge, c.bridge);
  }
  if (has_part(parts, RigPart::kFc)) {
    if (buses.can_fc == nullptr) throw std::logic_error("make_vehicle: the flight controller needs a CAN bus");
    n.fc = std::make_unique<bridge::FcNode>(*buses.can_fc, c.fc);
  }
  if (has_part(parts, RigPart::kLinkemu)) n.link = std::make_unique<linkemu::LinkEmulatorNode>(c.link);
  if (has_part(parts, RigPart::kVehicle)) {
    n.tools = std::make_unique<vehicle::ToolServerNode>(c.tool_server);
    n.monitor = std::make_unique<vehicle::AirspaceMonitorNode>(c.monitor);
  }
  return n;
}

}  // namespace a3::rigs
