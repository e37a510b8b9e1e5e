// SUNDIALS ARKODE's ERKStep with a fixed step and the classical fourth-order Runge-Kutta table
// over the same model: the library alternative to dynamics/rk4_integrator.*, kept here only to
// measure it against the hand-written one (bench_dynamics_virtual, "alone" rows). The same step
// rule (equal steps of at most 0.4 x the motor's fastest time constant, a stop time at every
// requested time), ground contact by ARKODE's root finding; no battery event (the benchmark's
// flights never empty it). Header-only, benchmark code.
#pragma once

#include <arkode/arkode_butcher.h>
#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dynamics/integrator.hpp"
#include "dynamics/rk4_integrator.hpp"

namespace a3::bench {

class ArkodeErkIntegrator final : public dynamics::Integrator {
 public:
  ArkodeErkIntegrator(const dynamics::QuadrotorModel& model, dynamics::WindField& wind)
      : Integrator(model, wind), max_step_s_(dynamics::default_rk4_step_s(model.params())) {
    check(SUNContext_Create(nullptr, &context_), "SUNContext_Create");
    y_ = N_VNew_Serial(dynamics::kStateSize, context_);
    dynamics::pack_state(state_, N_VGetArrayPointer(y_));
    mem_ = ERKStepCreate(&ArkodeErkIntegrator::rhs, 0.0, y_, context_);
    if (mem_ == nullptr) throw std::runtime_error("ERKStepCreate failed");
    double c[4] = {0.0, 0.5, 0.5, 1.0};
    double a[16] = {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0};
    double b[4] = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
    table_ = ARKodeButcherTable_Create(4, 4, 0, c, a, b, nullptr);
    check(ERKStepSetTable(mem_, table_), "ERKStepSetTable");
    check(ERKStepSetUserData(mem_, this), "ERKStepSetUserData");
    check(ERKStepSetFixedStep(mem_, max_step_s_), "ERKStepSetFixedStep");
    check(ERKStepSetMaxNumSteps(mem_, 100000), "ERKStepSetMaxNumSteps");
    check(ERKStepRootInit(mem_, 1, &ArkodeErkIntegrator::roots), "ERKStepRootInit");
  }
  ~ArkodeErkIntegrator() override {
    ERKStepFree(&mem_);
    ARKodeButcherTable_Free(table_);
    N_VDestroy(y_);
    SUNContext_Free(&context_);
  }

  std::string name() const override { return "arkode-erk"; }
  long steps() const {
    long n = 0;
    ERKStepGetNumSteps(mem_, &n);
    return n;
  }

 private:
  static void check(int flag, const char* what) {
    if (flag < 0) throw std::runtime_error(std::string("ARKODE: ") + what + " failed (" + std::to_string(flag) + ")");
  }

  static int rhs(double t, N_Vector y, N_Vector ydot, void* user) {
    auto* self = static_cast<ArkodeErkIntegrator*>(user);
    self->model_.derivatives(N_VGetArrayPointer(y), self->command_, self->wind_.wind_W_mps(t), self->on_ground_,
                             N_VGetArrayPointer(ydot));
    return 0;
  }

  static int roots(double, N_Vector y, double* g, void* user) {
    const auto* self = static_cast<ArkodeErkIntegrator*>(user);
    const double* s = N_VGetArrayPointer(y);
    if (!self->on_ground_) {
      g[0] = s[dynamics::index::kP + 2];
      return 0;
    }
    dynamics::RotorSpeeds speeds;
    for (int i = 0; i < 4; ++i) speeds[i] = s[dynamics::index::kRotor + i];
    g[0] = self->model_.weight_N() - self->model_.total_thrust_N(speeds);
    return 0;
  }

  void on_reset() override { need_reset_ = true; }

  void restart() {
    if (on_ground_ && model_.total_thrust_N(state_.rotor_speed_radps) > model_.weight_N()) {
      liftoff(time_s_, state_.p_W_m);
      state_.p_W_m.z() = 1e-6;
    }
    dynamics::pack_state(state_, N_VGetArrayPointer(y_));
    check(ERKStepReset(mem_, time_s_, y_), "ERKStepReset");
    need_reset_ = false;
  }

  void on_root(double t_s) {
    if (on_ground_) {
      liftoff(t_s, state_.p_W_m);
      state_.p_W_m.z() = 1e-6;
      return;
    }
    touchdown(t_s, state_.p_W_m, state_.v_W_mps.z());
    settle_on_ground();
    if (model_.total_thrust_N(state_.rotor_speed_radps) > model_.weight_N()) {
      on_ground_ = false;
      state_.p_W_m.z() = 1e-6;
    }
  }

  void integrate(double t_end_s, const dynamics::RotorSpeeds& command_radps) override {
    if (command_radps != command_) {
      command_ = command_radps;
      need_reset_ = true;
    }
    // Equal steps that land on t_end_s, as the RK4 integrator takes them.
    const double steps = std::max(1.0, std::ceil((t_end_s - time_s_) / max_step_s_ - 1e-9));
    check(ERKStepSetFixedStep(mem_, (t_end_s - time_s_) / steps), "ERKStepSetFixedStep");
    while (true) {
      if (need_reset_) restart();
      check(ERKStepSetStopTime(mem_, t_end_s), "ERKStepSetStopTime");
      double t = time_s_;
      const int flag = ERKStepEvolve(mem_, t_end_s, y_, &t, ARK_NORMAL);
      check(flag, "ERKStepEvolve");
      state_ = dynamics::unpack_state(N_VGetArrayPointer(y_));
      if (flag != ARK_ROOT_RETURN) {
        time_s_ = t_end_s;
        break;
      }
      time_s_ = t;
      on_root(t);
      need_reset_ = true;
    }
    state_.q_WB.normalize();
  }

  double max_step_s_;
  SUNContext context_ = nullptr;
  N_Vector y_ = nullptr;
  void* mem_ = nullptr;
  ARKodeButcherTable table_ = nullptr;
  dynamics::RotorSpeeds command_{};
  bool need_reset_ = true;
};

}  // namespace a3::bench
