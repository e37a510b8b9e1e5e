// The vehicle model integrated by the Open Dynamics Engine: each fixed step (0.5 ms by default,
// shortened to land on the requested time) the model's forces and torques are applied to a
// dBody and ODE's dWorldStep advances it; the ground is an ODE plane, and contact goes through
// ODE's collision detection and contact joints (no bounce). Rotor speeds follow the exact
// solution of the motor lag over each step; energy is integrated with the trapezoidal rule.
#pragma once

#include <ode/ode.h>

#include "dynamics/integrator.hpp"

namespace a3::dynamics {

class OdeIntegrator final : public Integrator {
 public:
  OdeIntegrator(const QuadrotorModel& model, WindField& wind, double step_s);
  ~OdeIntegrator() override;

  std::string name() const override { return "ode"; }
  double step_s() const { return step_s_; }

 private:
  void on_reset() override;
  void integrate(double t_end_s, const RotorSpeeds& command_radps) override;
  void step(double dt_s, const RotorSpeeds& command_radps);
  void read_body();
  int collide();
  static void near_callback(void* data, dGeomID a, dGeomID b);

  double step_s_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  dBodyID body_ = nullptr;
  dGeomID ground_ = nullptr;
  dGeomID hull_ = nullptr;
  int contact_count_ = 0;
  bool in_contact_ = false;
};

}  // namespace a3::dynamics
