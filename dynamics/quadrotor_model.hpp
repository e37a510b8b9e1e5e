// The quadrotor's equations of motion: a 6-DoF rigid body with four rotors in X configuration
// (thrust k_f ω², drag torque k_m ω², first-order motor lag), linear plus quadratic drag,
// gravity, and the electrical power the rotors and payloads draw. Pure functions of state and
// inputs, shared by both integrators. Rotor order and spin (PX4 quad-X, see dynamics/README.md):
// 0 front-right CCW, 1 rear-left CCW, 2 front-left CW, 3 rear-right CW.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>

#include "dynamics/vehicle_params.hpp"
#include "dynamics/vehicle_state.hpp"

namespace a3::dynamics {

using RotorSpeeds = std::array<double, 4>;

struct Wrench {
  Eigen::Vector3d force_W_N = Eigen::Vector3d::Zero();    // total, gravity included
  Eigen::Vector3d torque_B_Nm = Eigen::Vector3d::Zero();  // about the centre of mass
};

class QuadrotorModel {
 public:
  explicit QuadrotorModel(VehicleParams params);

  const VehicleParams& params() const { return params_; }
  double mass_kg() const { return mass_kg_; }
  double weight_N() const { return mass_kg_ * kGravity_mps2; }

  // Rotor positions in the body frame (FLU) and spin (+1 CCW seen from above, -1 CW).
  const std::array<Eigen::Vector3d, 4>& rotor_positions_B_m() const { return rotor_p_B_; }
  static constexpr std::array<double, 4> kSpin = {+1.0, +1.0, -1.0, -1.0};

  // The small functions below are inline: the right-hand side calls them in every evaluation.
  double rotor_thrust_N(double speed_radps) const {
    return params_.rotor.thrust_coeff_N_per_radps2 * speed_radps * speed_radps;
  }
  double total_thrust_N(const RotorSpeeds& speeds) const {
    double t = 0.0;
    for (double w : speeds) t += rotor_thrust_N(w);
    return t;
  }
  Wrench wrench(const VehicleState& s, const Eigen::Vector3d& wind_W_mps) const;
  // What an accelerometer at the centre of mass reads (specific force, body frame).
  Eigen::Vector3d specific_force_B_mps2(const VehicleState& s, const Eigen::Vector3d& wind_W_mps) const;

  // The motor's time constant toward a command: spinning up or down.
  double lag_time_constant_s(double speed_radps, double command_radps) const {
    return command_radps >= speed_radps ? params_.rotor.time_constant_up_s : params_.rotor.time_constant_down_s;
  }
  // Motor lag: dω/dt toward the command, faster up than down.
  double rotor_acceleration_radps2(double speed_radps, double command_radps) const {
    return (command_radps - speed_radps) / lag_time_constant_s(speed_radps, command_radps);
  }
  // ω(t + dt) for a command held over dt (exact solution of the lag).
  double rotor_speed_after(double speed_radps, double command_radps, double dt_s) const;

  // Electrical power: rotor induced power T^1.5 / (FM √(2ρA)) over the powertrain efficiency,
  // plus avionics and payloads.
  double electrical_power_W(const RotorSpeeds& speeds) const {
    double rotor_W = 0.0;
    for (double w : speeds) {
      const double t = rotor_thrust_N(w);
      rotor_W += t * std::sqrt(t) * induced_power_factor_;
    }
    return rotor_W / params_.battery.powertrain_efficiency + params_.battery.avionics_power_W +
           params_.payload_power_W;
  }
  double battery_energy_J() const {
    return params_.battery.capacity_Ah * 3600.0 * params_.battery.cells * params_.battery.cell_nominal_V;
  }

  // d/dt of the packed state (vehicle_state.hpp). On the ground the body does not move (only
  // rotors and energy evolve).
  void derivatives(const double* y, const RotorSpeeds& command_radps,
                   const Eigen::Vector3d& wind_W_mps, bool on_ground, double* dydt) const;

  // Throttle (0..1, as an ESC takes it) to rotor speed command: ω = throttle · ω_max.
  double throttle_to_speed_radps(double throttle) const {
    return std::clamp(throttle, 0.0, 1.0) * params_.rotor.max_speed_radps;
  }
  // The rotor speed, and the throttle, at which the four rotors carry the vehicle's weight.
  double hover_speed_radps() const;
  double hover_throttle() const;

 private:
  VehicleParams params_;
  double mass_kg_;
  Eigen::Vector3d inertia_kgm2_;
  std::array<Eigen::Vector3d, 4> rotor_p_B_;
  double induced_power_factor_;  // 1 / (FM √(2 ρ A))
};

}  // namespace a3::dynamics
