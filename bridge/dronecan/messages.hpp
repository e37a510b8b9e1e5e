// Every DroneCAN message type the rig speaks, and a type list to iterate over them.
#pragma once

#include <tuple>

#include "bridge/dronecan/msg/a3_fc.hpp"
#include "bridge/dronecan/msg/a3_fc_refusal.hpp"
#include "bridge/dronecan/msg/a3_sim.hpp"
#include "bridge/dronecan/msg/actuator.hpp"
#include "bridge/dronecan/msg/ahrs.hpp"
#include "bridge/dronecan/msg/air_data.hpp"
#include "bridge/dronecan/msg/esc.hpp"
#include "bridge/dronecan/msg/gnss.hpp"
#include "bridge/dronecan/msg/power.hpp"
#include "bridge/dronecan/msg/protocol.hpp"
#include "bridge/dronecan/msg/safety.hpp"

namespace a3::bridge {

// Top-level message types (those with a data type ID), standard first, then the project's.
using MessageTypes =
    std::tuple<NodeStatus, EscRawCommand, EscStatus, AhrsRawImu, MagneticFieldStrength2,
               GnssFix2, StaticPressure, StaticTemperature, BatteryInfo, ActuatorArrayCommand,
               ArmingStatus, FcCommand, FcStatus, FcCommandRefused, SimClock>;
// Types used only inside others.
using NestedTypes = std::tuple<Timestamp, GnssEcefPositionVelocity, ActuatorCommand>;

}  // namespace a3::bridge
