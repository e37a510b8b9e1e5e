// CVODE integration of the vehicle model.
#include "dynamics/cvode_integrator.hpp"

#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace a3::dynamics {
namespace {

constexpr double kMaxStep_s = 0.5;

void check(int flag, const char* what) {
  if (flag < 0) {
    throw std::runtime_error(std::string("CVODE: ") + what + " failed: " + CVodeGetReturnFlagName(flag));
  }
}

// Absolute tolerances per component: position and velocity to a micrometre (per second), the
// quaternion to 1e-9, body rates to 1e-8 rad/s, rotor speeds to 1e-3 rad/s, energy to 1 mJ.
void set_absolute_tolerances(N_Vector v) {
  double* a = N_VGetArrayPointer(v);
  for (int i = 0; i < 3; ++i) {
    a[index::kP + i] = 1e-6;
    a[index::kV + i] = 1e-6;
    a[index::kW + i] = 1e-8;
  }
  for (int i = 0; i < 4; ++i) {
    a[index::kQ + i] = 1e-9;
    a[index::kRotor + i] = 1e-3;
  }
  a[index::kEnergy] = 1e-3;
}

}  // namespace

CvodeIntegrator::CvodeIntegrator(const QuadrotorModel& model, WindField& wind, double relative_tolerance)
    : Integrator(model, wind), relative_tolerance_(relative_tolerance) {
  if (!(relative_tolerance > 0.0 && relative_tolerance < 1.0)) {
    throw std::invalid_argument("CVODE relative tolerance must be in (0, 1), got " +
                                std::to_string(relative_tolerance));
  }
  check(SUNContext_Create(nullptr, &context_), "SUNContext_Create");
  y_ = N_VNew_Serial(kStateSize, context_);
  abs_tolerance_ = N_VNew_Serial(kStateSize, context_);
  if (y_ == nullptr || abs_tolerance_ == nullptr) throw std::runtime_error("CVODE: out of memory");
  set_absolute_tolerances(abs_tolerance_);
  pack_state(state_, N_VGetArrayPointer(y_));
  cvode_ = CVodeCreate(CV_ADAMS, context_);
  if (cvode_ == nullptr) throw std::runtime_error("CVODE: CVodeCreate failed");
  check(CVodeInit(cvode_, &CvodeIntegrator::rhs, 0.0, y_), "CVodeInit");
  check(CVodeSVtolerances(cvode_, relative_tolerance_, abs_tolerance_), "CVodeSVtolerances");
  check(CVodeSetUserData(cvode_, this), "CVodeSetUserData");
  nonlinear_solver_ = SUNNonlinSol_FixedPoint(y_, 0, context_);
  if (nonlinear_solver_ == nullptr) throw std::runtime_error("CVODE: SUNNonlinSol_FixedPoint failed");
  check(CVodeSetNonlinearSolver(cvode_, nonlinear_solver_), "CVodeSetNonlinearSolver");
  check(CVodeSetMaxNumSteps(cvode_, 200000), "CVodeSetMaxNumSteps");
  // While nothing changes (idle on the ground) the steps would grow to minutes: cap them so
  // the wind is sampled at its own pace and the solver never reaches far past the present.
  check(CVodeSetMaxStep(cvode_, kMaxStep_s), "CVodeSetMaxStep");
  check(CVodeRootInit(cvode_, 2, &CvodeIntegrator::roots), "CVodeRootInit");
  check(CVodeSetNoInactiveRootWarn(cvode_), "CVodeSetNoInactiveRootWarn");
}

CvodeIntegrator::~CvodeIntegrator() {
  if (cvode_ != nullptr) CVodeFree(&cvode_);
  if (nonlinear_solver_ != nullptr) SUNNonlinSolFree(nonlinear_solver_);
  if (abs_tolerance_ != nullptr) N_VDestroy(abs_tolerance_);
  if (y_ != nullptr) N_VDestroy(y_);
  if (context_ != nullptr) SUNContext_Free(&context_);
}

CvodeIntegrator::Stats CvodeIntegrator::since_restart() const {
  Stats s;
  CVodeGetNumSteps(cvode_, &s.steps);
  CVodeGetNumRhsEvals(cvode_, &s.rhs_evaluations);
  CVodeGetNumErrTestFails(cvode_, &s.error_test_failures);
  CVodeGetNumNonlinSolvConvFails(cvode_, &s.convergence_failures);
  return s;
}

CvodeIntegrator::Stats CvodeIntegrator::stats() const {
  const Stats now = since_restart();
  Stats s = before_restart_;
  s.steps += now.steps;
  s.rhs_evaluations += now.rhs_evaluations;
  s.error_test_failures += now.error_test_failures;
  s.convergence_failures += now.convergence_failures;
  s.restarts = restarts_;
  return s;
}

void CvodeIntegrator::on_reset() {
  need_restart_ = true;
  if (on_ground_ && !crashed_ && model_.total_thrust_N(state_.rotor_speed_radps) > model_.weight_N()) {
    on_ground_ = false;
  }
}

int CvodeIntegrator::rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* self = static_cast<CvodeIntegrator*>(user);
  try {
    self->model_.derivatives(N_VGetArrayPointer(y), self->command_, self->wind_.wind_W_mps(t),
                             self->on_ground_, N_VGetArrayPointer(ydot));
  } catch (...) {
    return -1;  // unrecoverable: CVODE reports CV_RHSFUNC_FAIL
  }
  return 0;
}

int CvodeIntegrator::roots(sunrealtype, N_Vector y, sunrealtype* g, void* user) {
  const auto* self = static_cast<CvodeIntegrator*>(user);
  const double* s = N_VGetArrayPointer(y);
  if (self->crashed_) {
    g[0] = -1.0;
  } else if (self->on_ground_) {
    // Lift-off when the rotors' thrust exceeds the weight (the vehicle is level on the ground).
    RotorSpeeds speeds;
    for (int i = 0; i < 4; ++i) speeds[i] = s[index::kRotor + i];
    g[0] = self->model_.total_thrust_N(speeds) - self->model_.weight_N();
  } else {
    g[0] = s[index::kP + 2];  // altitude: touchdown when it reaches 0
  }
  g[1] = self->battery_empty_ ? -1.0 : self->model_.battery_energy_J() - s[index::kEnergy];
  return 0;
}

void CvodeIntegrator::restart() {
  before_restart_ = stats();
  // Root finding only sees sign changes after the initial point: a vehicle on the ground that
  // already has more thrust than weight lifts off now (or it would stay down for good).
  if (on_ground_ && !crashed_ && model_.total_thrust_N(state_.rotor_speed_radps) > model_.weight_N()) {
    liftoff(time_s_, state_.p_W_m);
    state_.p_W_m.z() = 1e-6;
  }
  pack_state(state_, N_VGetArrayPointer(y_));
  check(CVodeReInit(cvode_, time_s_, y_), "CVodeReInit");
  // Touchdown is a descent through z = 0, lift-off a rise of thrust above weight; the battery
  // empties once.
  int directions[2] = {on_ground_ ? +1 : -1, -1};
  check(CVodeSetRootDirection(cvode_, directions), "CVodeSetRootDirection");
  ++restarts_;
  need_restart_ = false;
}

void CvodeIntegrator::integrate(double t_end_s, const RotorSpeeds& command_radps) {
  if (command_radps != command_) {
    command_ = command_radps;
    need_restart_ = true;
  }
  while (true) {
    if (need_restart_) restart();
    sunrealtype t = time_s_;
    const int flag = CVode(cvode_, t_end_s, y_, &t, CV_NORMAL);
    check(flag, "CVode");
    state_ = unpack_state(N_VGetArrayPointer(y_));
    if (flag != CV_ROOT_RETURN) {
      time_s_ = t_end_s;
      // Root finding misses a descent that starts exactly at z = 0 (the root is inactive at
      // the initial point): never let the vehicle pass through the floor.
      if (!on_ground_ && state_.p_W_m.z() < 0.0) {
        touchdown(t_end_s, state_.p_W_m, state_.v_W_mps.z());
        settle_on_ground();
        if (crashed_) command_ = RotorSpeeds{};
        need_restart_ = true;
      }
      break;
    }
    time_s_ = t;
    int found[2] = {0, 0};
    check(CVodeGetRootInfo(cvode_, found), "CVodeGetRootInfo");
    if (found[1] != 0) {
      empty_battery(t);
      command_ = RotorSpeeds{};
    }
    if (found[0] != 0) {
      if (on_ground_) {
        liftoff(t, state_.p_W_m);
      } else {
        touchdown(t, state_.p_W_m, state_.v_W_mps.z());
        settle_on_ground();
        if (crashed_) {
          command_ = RotorSpeeds{};
        } else if (model_.total_thrust_N(state_.rotor_speed_radps) > model_.weight_N()) {
          // Touched down with more thrust than weight: it stays airborne, just above the floor
          // so that the next descent is a sign change the root finding sees.
          on_ground_ = false;
          state_.p_W_m.z() = 1e-6;
        }
      }
    }
    need_restart_ = true;
  }
  // Keep the attitude a unit quaternion; restart the solver only if it drifted measurably.
  const double norm = state_.q_WB.norm();
  if (std::abs(norm - 1.0) > 1e-9) {
    state_.q_WB.normalize();
    need_restart_ = true;
  }
}

}  // namespace a3::dynamics
