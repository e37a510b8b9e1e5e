// The parts a rig is made of, as `a3rig node part` names them: the ground side (recorder, LCM
// log, conversation) and the parts of a vehicle (dynamics, bridge, fc, linkemu, vehicle).
#pragma once

#include <string>
#include <vector>

namespace a3::rigs {

enum class RigPart { kGround, kDynamics, kBridge, kFc, kLinkemu, kVehicle };
const std::vector<RigPart>& rig_parts_outside_ground();  // dynamics, bridge, fc, linkemu, vehicle
std::vector<RigPart> all_rig_parts();                     // the ground first, then those
std::string to_string(RigPart part);
RigPart parse_rig_part(const std::string& name);  // throws std::invalid_argument listing the names
bool has_part(const std::vector<RigPart>& parts, RigPart part);

}  // namespace a3::rigs
