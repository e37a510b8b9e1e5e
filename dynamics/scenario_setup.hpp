// Setting up the dynamics for a flight's start, from typed values (the rig parses the
// scenario or episode: rigs/scenario/initial_state.hpp): the start pose (ENU metres, yaw in
// degrees from east), the mean wind (speed and the direction it blows from, corpus
// convention), the payloads carried and the battery's state of charge.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "dynamics/dynamics_node.hpp"
#include "dynamics/vehicle_params.hpp"

namespace a3::dynamics {

struct FlightStart {
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
  double yaw_deg = 0.0;
  double wind_mps = 0.0;
  double wind_dir_deg = 0.0;
  std::vector<Payload> payloads;
  double battery_pct = 100.0;  // (0, 100]: the energy already drawn is the rest
};

// Applies the start to config (params must already hold the airframe; the payloads are
// added). With start_on_ground the vehicle starts at z = 0 below the pose; otherwise at the
// pose, rotors at hover speed. Throws std::invalid_argument for a negative or non-finite
// wind or a battery outside (0, 100].
void apply_flight_start(const FlightStart& start, bool start_on_ground, DynamicsNodeConfig& config);

}  // namespace a3::dynamics
