// Vehicle channel names.
#include "common/channel.hpp"

namespace a3::common {

std::string vehicle_channel_name(std::string_view base, VehicleId vehicle) {
  if (vehicle == 0) return std::string(base);
  constexpr std::string_view kPrefix = "A3_";
  const std::string tag = "V" + std::to_string(vehicle) + "_";
  if (base.substr(0, kPrefix.size()) == kPrefix) {
    return std::string(kPrefix) + tag + std::string(base.substr(kPrefix.size()));
  }
  return tag + std::string(base);
}

}  // namespace a3::common
