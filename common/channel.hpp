// A bus channel declared once with its message type (PX4 ties every topic to its message), so
// `Bus::publish` and `Bus::subscribe` take the type from the channel, and scoped:
//   RigChannel<Msg>      one for the whole rig (the clock, the episode, node statistics);
//   VehicleChannel<Msg>  one per vehicle: `.of(vehicle)` names vehicle n's copy.
// Vehicle 0 keeps the plain name ("A3_STATE"), so logs, lcm-spy and scripts keep working;
// vehicle n >= 1 inserts "V<n>_" after the "A3_" prefix ("A3_V1_STATE", "A3_V2_FC_CMD").
// A node names every channel it publishes or subscribes in its ports() (node.hpp): the
// runtime holds it to them and `a3rig topology` draws the graph from them.
#pragma once

#include <string>
#include <string_view>

namespace a3::common {

using VehicleId = int;  // 0 .. N-1 in a rig of N vehicles

// The LCM name of `base` for `vehicle` (see above).
std::string vehicle_channel_name(std::string_view base, VehicleId vehicle);

// A channel resolved to its name on the bus, with its message type: what the bus takes.
template <typename Msg>
struct TypedChannel {
  using Message = Msg;
  std::string name;
};

template <typename Msg>
struct RigChannel {
  using Message = Msg;
  const char* name;
  operator TypedChannel<Msg>() const { return {name}; }  // NOLINT: a rig channel is already resolved
};

template <typename Msg>
struct VehicleChannel {
  using Message = Msg;
  const char* base;  // vehicle 0's name
  TypedChannel<Msg> of(VehicleId vehicle) const { return {vehicle_channel_name(base, vehicle)}; }
};

}  // namespace a3::common
