// How each objective is judged, in one place: the numbers the mission tracker applies and the
// sentence the brief gives the agent, so what an agent is told is what the judge does.
#pragma once

#include <string>

#include "agent/mission/mission.hpp"

namespace a3::agent {

// Survey captures count inside the area or within this distance of its edge (a lawnmower's line
// ends lie on the edge).
constexpr double kSurveyEdgeMargin_m = 10.0;
// A delivery counts at or below the drop altitude plus this: the altitude error the flight
// controller holds in a hover (a vehicle sent to exactly the drop altitude settles within it).
constexpr double kDropAltitudeTolerance_m = 0.5;
// ...held this long without a break, within the objective's radius of the drop point.
constexpr double kDropDwell_s = 1.0;
// A thermal search sees its target from at most this far above the objective's altitude.
constexpr double kThermalSightAbove_m = 40.0;

// The highest altitude at which a delivery objective's drop counts.
inline double drop_ceiling_m(const Objective& o) { return o.drop_altitude_m + kDropAltitudeTolerance_m; }

// One sentence: when the judge counts the objective done.
std::string objective_rule_text(const Objective& objective);

}  // namespace a3::agent
