// One interface over the integrators of the vehicle model (fixed-step RK4, CVODE, Open Dynamics Engine):
// advance the state to a time with the rotor commands held constant (zero-order hold), report
// ground contact, crashes and an empty battery as events.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

#include "dynamics/integrator_kind.hpp"
#include "dynamics/quadrotor_model.hpp"
#include "dynamics/wind_field.hpp"

namespace a3::dynamics {

struct DynamicsEvent {
  enum class Kind { kTouchdown, kLiftoff, kCrash, kBatteryEmpty };
  Kind kind;
  double time_s;
  Eigen::Vector3d p_W_m;
  double vertical_speed_mps;  // at touchdown or crash (negative: descending)
};
const char* to_string(DynamicsEvent::Kind kind);

class Integrator {
 public:
  // model and wind outlive the integrator.
  Integrator(const QuadrotorModel& model, WindField& wind);
  virtual ~Integrator() = default;
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  virtual std::string name() const = 0;

  // Starts from state s at time t_s. A state at or below z = 0 starts on the ground.
  void reset(const VehicleState& s, double t_s);
  // Integrates to t_end_s (> time_s()) with the rotor speed commands held constant. A crashed
  // vehicle or an empty battery spins the rotors down whatever the command.
  void advance_to(double t_end_s, const RotorSpeeds& command_radps);

  const VehicleState& state() const { return state_; }
  double time_s() const { return time_s_; }
  bool on_ground() const { return on_ground_; }
  bool crashed() const { return crashed_; }
  bool battery_empty() const { return battery_empty_; }
  // Events since the last call.
  std::vector<DynamicsEvent> take_events();

  const QuadrotorModel& model() const { return model_; }
  WindField& wind() { return wind_; }

 protected:
  virtual void on_reset() = 0;
  // Integrates from time_s_ to t_end_s with the effective command; updates state_, time_s_,
  // on_ground_ and records events (via touchdown(), liftoff(), empty_battery()).
  virtual void integrate(double t_end_s, const RotorSpeeds& command_radps) = 0;

  // Contact bookkeeping shared by both integrators. touchdown() decides crash or landing.
  void touchdown(double t_s, const Eigen::Vector3d& p_W_m, double vertical_speed_mps);
  void liftoff(double t_s, const Eigen::Vector3d& p_W_m);
  void empty_battery(double t_s);
  RotorSpeeds effective_command(const RotorSpeeds& command) const;
  // Inelastic contact with friction: state_ stops on the floor, level, keeping its heading.
  void settle_on_ground();

  const QuadrotorModel& model_;
  WindField& wind_;
  VehicleState state_;
  double time_s_ = 0.0;
  bool on_ground_ = false;
  bool crashed_ = false;
  bool battery_empty_ = false;
  std::vector<DynamicsEvent> events_;
};

struct IntegratorOptions {
  // RK4: the longest step; 0 takes 0.4 x the motor's fastest time constant (rk4_integrator.hpp)
  double rk4_max_step_s = 0.0;
  // CVODE
  double relative_tolerance = 1e-8;
  // ODE
  double ode_step_s = 0.0005;
};

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind, const QuadrotorModel& model,
                                            WindField& wind, const IntegratorOptions& options = {});

}  // namespace a3::dynamics
