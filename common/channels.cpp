// The declared channels, listed.
#include "common/channels.hpp"

namespace a3::common::channels {

std::vector<DeclaredChannel> declared_channels(VehicleId vehicle) {
  std::vector<DeclaredChannel> out;
#define A3_LIST_VEHICLE_CHANNEL(constant, type, text) \
  out.push_back({constant.of(vehicle).name, std::string("a3lcm.") + a3lcm::type::getTypeName(), true});
#define A3_LIST_RIG_CHANNEL(constant, type, text) out.push_back({text, std::string("a3lcm.") + a3lcm::type::getTypeName(), false});
  A3_VEHICLE_CHANNELS(A3_LIST_VEHICLE_CHANNEL)
  A3_RIG_CHANNELS(A3_LIST_RIG_CHANNEL)
#undef A3_LIST_VEHICLE_CHANNEL
#undef A3_LIST_RIG_CHANNEL
  return out;
}

}  // namespace a3::common::channels
