// The battery cost of flying, as the safety gate estimates it: power drawn × time, with the
// time of a leg from its horizontal length at the ground speed the vehicle makes good (the
// commanded speed in calm air without a ground-speed model; the wind triangle with the fc's
// limits and the vehicle's wind estimate with one, ground_speed.hpp) and its climb and descent
// at the vertical speeds, and the return home flown the way the flight controller's
// RETURN_HOME does it (climb to the return altitude, fly home, land).
#pragma once

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

#include "vehicle/ground_speed.hpp"

namespace a3::vehicle {

struct EnergyModel {
  // Electrical power in hover with the scenario's payloads on board (rotors, avionics, payload
  // power), W. The orchestrator derives it from the airframe (dynamics); 180 W is the 3DR Iris.
  double hover_power_w = 180.0;
  // Forward flight draws this multiple of the hover power (drag, wind and manoeuvres).
  double cruise_power_factor = 1.1;
  // Usable battery energy, Wh (capacity_Ah · cells · nominal cell V; Iris 3S 5.1 Ah = 56.6 Wh).
  double battery_capacity_wh = 56.6;
  // Speeds the estimate assumes: cruise when a command gives none (the fc's default), climb
  // and descent (conservative: the fc lands at 0.7..2 m/s).
  double cruise_speed_mps = 5.0;
  double climb_speed_mps = 2.0;
  double descent_speed_mps = 1.0;
  // Time spent settling at each waypoint of a route before the next leg, s.
  double settle_s_per_waypoint = 3.0;
  // The estimate is multiplied by this before it is compared with the battery left.
  double margin_factor = 1.2;
  // What the vehicle makes good over the ground at a commanded speed (shared with the tool
  // server, which keeps its wind up to date). nullptr: the commanded speed, as in calm air.
  std::shared_ptr<const GroundSpeedModel> ground_speed;

  // Battery share drawn per second of hover, and per metre of level flight at speed_mps over
  // the ground (%).
  double percent_per_s() const;
  double percent_per_m(double speed_mps) const;
  // Time of the horizontal part of a → b flown at speed_mps (commanded); infinity when the
  // wind does not let the vehicle make good that course.
  double horizontal_time_s(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double speed_mps) const;
  // Time of the vertical part of a → b at the climb or descent speed.
  double vertical_time_s(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
  // Time and battery share of the straight leg a → b at speed_mps (horizontal, commanded),
  // with the margin factor applied to the share.
  // The time is the climb (or descent) then the horizontal part: an upper bound for budgets.
  double leg_time_s(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double speed_mps) const;
  // The time as the fc flies a go-to, climbing (or descending) while it flies: the longer of the
  // two parts. What the swarm's conflict prediction expects; leg_time_s for budgets.
  double flown_leg_time_s(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double speed_mps) const;
  double leg_percent(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double speed_mps) const;
  // Through every waypoint in order, settling at each.
  double route_time_s(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& waypoints,
                      double speed_mps) const;
  double route_percent(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& waypoints,
                       double speed_mps) const;

  // Throws std::invalid_argument naming the field ("energy.hover_power_w must be > 0, got -1").
  void validate(const std::string& where) const;
};

// The legs of the flight controller's return home from p: climb (or keep altitude) to
// cruise_z = clamp(max(p.z, return_altitude_m, min_altitude_m), ≤ max_altitude_m), fly to
// above home at that altitude, descend to home. The returned points exclude p.
std::vector<Eigen::Vector3d> return_home_legs(const Eigen::Vector3d& p_W_m, const Eigen::Vector3d& home_W_m,
                                              double return_altitude_m, double min_altitude_m,
                                              double max_altitude_m);

}  // namespace a3::vehicle
