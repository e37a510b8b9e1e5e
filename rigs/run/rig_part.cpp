// The rig's parts and their names.
#include "rigs/run/rig_part.hpp"

#include <algorithm>
#include <stdexcept>

namespace a3::rigs {

const std::vector<RigPart>& rig_parts_outside_ground() {
  static const std::vector<RigPart> parts = {RigPart::kDynamics, RigPart::kBridge, RigPart::kFc, RigPart::kLinkemu,
                                             RigPart::kVehicle};
  return parts;
}

std::vector<RigPart> all_rig_parts() {
  std::vector<RigPart> parts = rig_parts_outside_ground();
  parts.insert(parts.begin(), RigPart::kGround);
  return parts;
}

std::string to_string(RigPart part) {
  switch (part) {
    case RigPart::kGround: return "ground";
    case RigPart::kDynamics: return "dynamics";
    case RigPart::kBridge: return "bridge";
    case RigPart::kFc: return "fc";
    case RigPart::kLinkemu: return "linkemu";
    case RigPart::kVehicle: return "vehicle";
  }
  return "?";
}

RigPart parse_rig_part(const std::string& name) {
  for (RigPart p : all_rig_parts()) {
    if (to_string(p) == name) return p;
  }
  throw std::invalid_argument("unknown rig part '" + name + "' (ground, dynamics, bridge, fc, linkemu, vehicle)");
}

bool has_part(const std::vector<RigPart>& parts, RigPart part) {
  return std::find(parts.begin(), parts.end(), part) != parts.end();
}

}  // namespace a3::rigs
