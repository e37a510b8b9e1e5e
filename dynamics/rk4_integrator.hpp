// The vehicle model integrated by the classical fourth-order Runge-Kutta method with a fixed
// step (the default integrator; CVODE stays the accuracy reference). A one-step method keeps no
// history, so a new rotor command, which an autopilot sends every period, costs nothing, where
// CVODE restarts its multistep history at every command (bench/dynamics/README.md).
//
// Step: each advance_to splits its interval into the fewest equal steps no longer than the
// maximum step, so it lands exactly on the requested time (no drift). The default maximum step
// is 0.4 x the motor's fastest time constant (5 ms for the Iris, 12.5 ms lag up): the lag is the
// model's fastest mode (1/tau = 80/s), and at lambda*h = 0.4 RK4 is well inside its stability
// interval (2.78) with a relative error per step of (lambda*h)^5/120, about 1e-4 of the speed
// change; the rigid-body modes are slower (tests/dynamics/test_integrators.cpp: within 1 cm and
// 0.5 deg of CVODE after 60 s of the closed-loop patrol flight).
//
// Events (touchdown, lift-off, an empty battery) are found inside a step by re-taking the step
// with a shorter length until the event's sign change is bracketed within 0.1 us (Illinois
// regula falsi); the state is then the one at the event, as with CVODE's root finding.
//
// Hand-written rather than SUNDIALS ARKODE's ERKStep with the same table and a fixed step:
// ARKODE's per-step bookkeeping (N_Vector operations, stop-time and step-size logic) cost
// more than the model's equations on an 18-element state (figures in bench/dynamics/README.md).
#pragma once

#include <array>

#include "dynamics/integrator.hpp"

namespace a3::dynamics {

// 0.4 x the faster of the motor's time constants (up, down): see the header comment.
double default_rk4_step_s(const VehicleParams& params);

class Rk4Integrator final : public Integrator {
 public:
  // max_step_s > 0; 0 selects default_rk4_step_s(model.params()).
  Rk4Integrator(const QuadrotorModel& model, WindField& wind, double max_step_s);

  std::string name() const override { return "rk4"; }
  double max_step_s() const { return max_step_s_; }

  struct Stats {
    long steps = 0;            // including the re-taken steps that locate an event
    long rhs_evaluations = 0;  // 4 per step
    long events = 0;           // touchdowns, lift-offs, empty battery
  };
  const Stats& stats() const { return stats_; }

 private:
  using State = std::array<double, kStateSize>;

  void on_reset() override;
  void integrate(double t_end_s, const RotorSpeeds& command_radps) override;
  void step_to(double t_next_s);
  void rk4_step(const State& y0, double t0_s, double h_s, State& y1);
  // Inline: three calls per step, mostly for a time already sampled.
  const Eigen::Vector3d& wind_at(double t_s) {
    if (t_s != wind_time_s_) sample_wind(t_s);
    return wind_W_mps_;
  }
  void sample_wind(double t_s);

  // Event functions: > 0 before, <= 0 at and after the event (whichever applies now).
  double contact_function(const State& y) const;
  double battery_function(const State& y) const;
  double locate_event(const State& y1, double h_s, double (Rk4Integrator::*g)(const State&) const,
                      State& y_event);
  void on_contact(double t_s);
  void on_battery_empty(double t_s);
  void lift_off_if_thrust_exceeds_weight();

  double max_step_s_;
  State y_{};
  RotorSpeeds command_{};
  double wind_time_s_ = -1.0;
  Eigen::Vector3d wind_W_mps_ = Eigen::Vector3d::Zero();
  Stats stats_;
};

}  // namespace a3::dynamics
