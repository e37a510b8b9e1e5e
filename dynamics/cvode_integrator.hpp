// The vehicle model integrated by SUNDIALS CVODE: variable-order, variable-step BDF with error
// control (relative tolerance 1e-8 by default; absolute tolerances per state component, see
// cvode_integrator.cpp), ground contact and an empty battery found by CVODE's root finding.
// The solver keeps its history while the inputs stay the same and restarts when they change.
#pragma once

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "dynamics/integrator.hpp"

namespace a3::dynamics {

class CvodeIntegrator final : public Integrator {
 public:
  CvodeIntegrator(const QuadrotorModel& model, WindField& wind, double relative_tolerance);
  ~CvodeIntegrator() override;

  std::string name() const override { return "cvode"; }

  struct Stats {
    long steps = 0;
    long rhs_evaluations = 0;
    long restarts = 0;
  };
  Stats stats() const;

 private:
  void on_reset() override;
  void integrate(double t_end_s, const RotorSpeeds& command_radps) override;
  void restart();
  void settle_on_ground();

  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user);
  static int roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user);

  double relative_tolerance_;
  SUNContext context_ = nullptr;
  N_Vector y_ = nullptr;
  N_Vector abs_tolerance_ = nullptr;
  SUNMatrix jacobian_ = nullptr;
  SUNLinearSolver linear_solver_ = nullptr;
  void* cvode_ = nullptr;
  RotorSpeeds command_{};
  bool need_restart_ = true;
  long restarts_ = 0;
};

}  // namespace a3::dynamics
