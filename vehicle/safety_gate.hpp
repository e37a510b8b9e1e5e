// The safety gate A_safe: what the tool server checks before any motion reaches the flight
// controller. Rules (numbers from GateConfig / EnergyModel):
//   - targets: altitude within the envelope [min, max]; inside the geofence by at least
//     geofence_margin_m; outside every no-fly zone by nfz_margin_m horizontally (the zone's
//     floor and ceiling widened by nfz_vertical_margin_m);
//   - legs (the straight path from the current position, and between waypoints): never
//     crossing the geofence boundary from inside, never passing within nfz_margin_m of a
//     no-fly zone (a leg that starts already inside a zone's margin may only move away from it);
//   - battery: battery now − estimated route cost − estimated return home from the route's
//     end (EnergyModel) must stay ≥ battery_reserve_pct;
//   - speed: at most max_speed_mps.
// Every check returns "" when it passes, else why, with the numbers.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "vehicle/energy_model.hpp"
#include "vehicle/ground_shared.hpp"

namespace a3::vehicle {

struct GateConfig {
  double geofence_margin_m = 5.0;      // ≥ the fc's fence margin, or the fc refuses what we pass
  double nfz_margin_m = 5.0;           // horizontal clearance to keep from no-fly zones
  double nfz_vertical_margin_m = 5.0;  // clearance above a zone's ceiling / below its floor
  double battery_reserve_pct = 25.0;   // battery left after the route and the return home
  double max_speed_mps = 12.0;         // the vehicle's horizontal speed limit (the fc's)
  double return_altitude_m = 30.0;     // the fc's return altitude (FcFailsafeParams)

  // Throws std::invalid_argument naming the field.
  void validate(const std::string& where) const;
};

struct BatteryEstimate {
  double now_pct = 0.0;
  double route_pct = 0.0;   // flying the waypoints, with the model's margin factor
  double return_pct = 0.0;  // returning home from the last waypoint and landing
  double left_pct = 0.0;    // now − route − return
};

class SafetyGate {
 public:
  // home_W_m: the take-off point (the return target).
  SafetyGate(Airspace airspace, GateConfig config, EnergyModel energy, Eigen::Vector3d home_W_m);

  // `what` names the point in the reason ("target", "waypoint 3").
  std::string check_target(const Eigen::Vector3d& p_W_m, const std::string& what) const;
  // `what` names the leg in the reason ("leg 2").
  std::string check_leg(const Eigen::Vector3d& a_W_m, const Eigen::Vector3d& b_W_m, const std::string& what) const;
  // Every waypoint as a target and every leg from start through them. Names "waypoint i" and
  // "leg i" (1-based) when there is more than one waypoint, "target" and "path" otherwise.
  std::string check_path(const Eigen::Vector3d& start_W_m, const std::vector<Eigen::Vector3d>& waypoints) const;
  BatteryEstimate estimate_battery(const Eigen::Vector3d& start_W_m, const std::vector<Eigen::Vector3d>& waypoints,
                                   double speed_mps, double battery_pct) const;
  std::string check_battery(const Eigen::Vector3d& start_W_m, const std::vector<Eigen::Vector3d>& waypoints,
                            double speed_mps, double battery_pct) const;
  std::string check_speed(double speed_mps) const;
  // check_speed, check_path, then check_battery.
  std::string check_route(const Eigen::Vector3d& start_W_m, const std::vector<Eigen::Vector3d>& waypoints,
                          double speed_mps, double battery_pct) const;
  // Landing at p: the vertical descent to the ground must not pass through a no-fly zone.
  std::string check_descent(const Eigen::Vector3d& p_W_m) const;

  const Airspace& airspace() const { return airspace_; }
  const GateConfig& config() const { return config_; }
  const EnergyModel& energy() const { return energy_; }
  const Eigen::Vector3d& home_W_m() const { return home_W_m_; }

 private:
  NoFlyZone widened(const NoFlyZone& zone) const;

  Airspace airspace_;
  GateConfig config_;
  EnergyModel energy_;
  Eigen::Vector3d home_W_m_;
};

// "(12.0, -3.5, 40.0)" for reasons and logs.
std::string format_point(const Eigen::Vector3d& p_W_m);

}  // namespace a3::vehicle
