// The vehicle model integrated by SUNDIALS CVODE: variable-order, variable-step Adams-Moulton
// with fixed-point iteration and error control (relative tolerance 1e-8 by default; absolute
// tolerances per state component, see cvode_integrator.cpp), ground contact and an empty
// battery found by CVODE's root finding. The solver keeps its history while the inputs stay
// the same and restarts when they change.
//
// Adams rather than BDF: the model is not stiff (its fastest mode is the motor lag, 1/τ = 80/s
// for the Iris, well inside Adams' stability region at the steps the tolerance needs), and
// with an autopilot's command changing every step the solver restarts every 10 ms: BDF then
// rebuilds and factors a difference-quotient Jacobian after every restart, which made it about
// 3x slower for the same accuracy (bench/dynamics/README.md).
#pragma once

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_nonlinearsolver.h>

#include "dynamics/integrator.hpp"

namespace a3::dynamics {

class CvodeIntegrator final : public Integrator {
 public:
  CvodeIntegrator(const QuadrotorModel& model, WindField& wind, double relative_tolerance);
  ~CvodeIntegrator() override;

  std::string name() const override { return "cvode"; }

  // Totals since construction (CVODE's own counters start again at every restart).
  struct Stats {
    long steps = 0;
    long rhs_evaluations = 0;
    long error_test_failures = 0;
    long convergence_failures = 0;  // of the fixed-point iteration
    long restarts = 0;              // command changes, ground contact, battery, renormalisation
  };
  Stats stats() const;

 private:
  void on_reset() override;
  void integrate(double t_end_s, const RotorSpeeds& command_radps) override;
  void restart();
  Stats since_restart() const;

  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user);
  static int roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user);

  double relative_tolerance_;
  SUNContext context_ = nullptr;
  N_Vector y_ = nullptr;
  N_Vector abs_tolerance_ = nullptr;
  SUNNonlinearSolver nonlinear_solver_ = nullptr;
  void* cvode_ = nullptr;
  RotorSpeeds command_{};
  bool need_restart_ = true;
  long restarts_ = 0;
  Stats before_restart_;  // totals up to the last restart
};

}  // namespace a3::dynamics
