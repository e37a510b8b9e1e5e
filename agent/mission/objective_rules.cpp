// The judge's rules as the brief states them.
#include "agent/mission/objective_rules.hpp"

#include "common/text_format.hpp"

namespace a3::agent {
namespace {

using common::formatted;

std::string delivery_rule(const Objective& o) {
  return formatted("Done when the vehicle stays within %g m (horizontally) of the drop point at or below %g m altitude "
                   "(the drop altitude %g m plus the flight controller's %g m hover tolerance) for %g s without a "
                   "break; the parcel is released there by itself (there is no release tool).",
                   o.radius_m, drop_ceiling_m(o), o.drop_altitude_m, kDropAltitudeTolerance_m, kDropDwell_s);
}

}  // namespace

std::string objective_rule_text(const Objective& o) {
  switch (o.type) {
    case ObjectiveType::kSurvey:
      return std::to_string(o.images_required) + " captures with the " + o.sensor + " camera taken inside the area " +
             formatted("or within %g m of its edge count; done at the last one.", kSurveyEdgeMargin_m);
    case ObjectiveType::kImagePoint:
      return "Done at a capture with the " + o.sensor + formatted(" camera taken within %g m (horizontally) of the point.", o.radius_m);
    case ObjectiveType::kDelivery:
      return delivery_rule(o);
    case ObjectiveType::kThermalSearch:
      return formatted("Done when the active thermal camera passes within %g m (horizontally) of the target (its place is not given), "
                       "at most %g m above the objective's altitude, or a thermal capture is taken there.",
                       o.radius_m, kThermalSightAbove_m);
    case ObjectiveType::kReturnAndLand:
      return formatted("Done while the vehicle is on the ground, disarmed, within %g m (horizontally) of home.", o.radius_m);
  }
  return "";
}

}  // namespace a3::agent
