// Whether a generated mission can be flown, judged with the rig's own numbers: the node
// configurations a run would use (make_rig_configs: airframe with payloads, fc limits, safety
// gate, energy model, planner), the ground station's path planner for the way out and the way
// home around no-fly zones, the safety gate for every other leg, the gate's battery estimate
// for the whole mission, and the airframe's top airspeed at the fc's tilt limit against the
// wind. Also estimates the mission's duration, from which the generator sets the time limit.
#pragma once

#include <string>

#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

struct MissionCheck {
  std::string problem;           // "" when the mission can be flown
  double route_time_s = 0.0;     // take-off, every leg and lawnmower, the way home and landing
  double max_airspeed_mps = 0.0; // level flight at the tilt limit with the payloads' drag
  double ground_speed_mps = 0.0; // the speed assumed into the wind
  double battery_left_pct = 0.0; // the gate's estimate after the whole mission
  // When each phase of the reference flight begins, seconds after take-off at the ground speed
  // (the climb, the transit to the first objective, the first objective's work, the way home).
  struct Phases {
    double transit_s = 0.0;
    double objective_s = 0.0;
    double home_s = 0.0;
  } phases;
};

// Survey lawnmower spacing of the reference policy (the scripted agent), metres.
double reference_spacing_m(const agent::Objective& objective);

// Throws common::InputError when the scenario's node configurations cannot be made (payload
// beyond the airframe's lift).
MissionCheck check_generated_mission(const Scenario& scenario);

}  // namespace a3::rigs
