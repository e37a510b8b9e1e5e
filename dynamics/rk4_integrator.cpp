// Fixed-step classical Runge-Kutta integration of the vehicle model.
#include "dynamics/rk4_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace a3::dynamics {
namespace {

constexpr double kStepOverTimeConstant = 0.4;
constexpr double kEventTolerance_s = 1e-7;  // 1.4 um of travel at a 14 m/s impact
constexpr int kMaxEventIterations = 100;
constexpr double kLiftoffHeight_m = 1e-6;   // above the floor, so a descent is a sign change

void normalise_quaternion(double* y) {
  double* q = y + index::kQ;
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (int i = 0; i < 4; ++i) q[i] /= norm;
}

}  // namespace

double default_rk4_step_s(const VehicleParams& params) {
  return kStepOverTimeConstant * std::min(params.rotor.time_constant_up_s, params.rotor.time_constant_down_s);
}

Rk4Integrator::Rk4Integrator(const QuadrotorModel& model, WindField& wind, double max_step_s)
    : Integrator(model, wind), max_step_s_(max_step_s == 0.0 ? default_rk4_step_s(model.params()) : max_step_s) {
  if (!(max_step_s_ > 0.0 && max_step_s_ <= 0.05)) {
    throw std::invalid_argument("RK4 maximum step must be in (0, 0.05] s, got " + std::to_string(max_step_s_));
  }
}

void Rk4Integrator::on_reset() {
  pack_state(state_, y_.data());
  wind_time_s_ = -1.0;
}

void Rk4Integrator::integrate(double t_end_s, const RotorSpeeds& command_radps) {
  command_ = command_radps;
  const double t0_s = time_s_;
  const double steps = std::max(1.0, std::ceil((t_end_s - t0_s) / max_step_s_ - 1e-9));
  const double h_s = (t_end_s - t0_s) / steps;
  const int n = static_cast<int>(steps);
  for (int k = 1; k < n; ++k) step_to(t0_s + k * h_s);
  step_to(t_end_s);
  state_ = unpack_state(y_.data());
}

void Rk4Integrator::step_to(double t_next_s) {
  while (time_s_ < t_next_s) {
    lift_off_if_thrust_exceeds_weight();
    const double h_s = t_next_s - time_s_;
    State y1;
    rk4_step(y_, time_s_, h_s, y1);
    const bool contact = contact_function(y_) > 0.0 && contact_function(y1) <= 0.0;
    const bool battery = battery_function(y_) > 0.0 && battery_function(y1) <= 0.0;
    if (!contact && !battery) {
      y_ = y1;
      normalise_quaternion(y_.data());
      time_s_ = t_next_s;
      return;
    }
    constexpr double kNever = std::numeric_limits<double>::infinity();
    State y_contact, y_battery;
    const double h_contact = contact ? locate_event(y1, h_s, &Rk4Integrator::contact_function, y_contact) : kNever;
    const double h_battery = battery ? locate_event(y1, h_s, &Rk4Integrator::battery_function, y_battery) : kNever;
    const bool contact_first = h_contact <= h_battery;
    const double h_event_s = contact_first ? h_contact : h_battery;
    y_ = contact_first ? y_contact : y_battery;
    normalise_quaternion(y_.data());
    time_s_ = h_event_s >= h_s ? t_next_s : time_s_ + h_event_s;
    if (contact_first) {
      on_contact(time_s_);
    } else {
      on_battery_empty(time_s_);
    }
  }
}

void Rk4Integrator::sample_wind(double t_s) {
  wind_W_mps_ = wind_.wind_W_mps(t_s);
  wind_time_s_ = t_s;
}

void Rk4Integrator::rk4_step(const State& y0, double t0_s, double h_s, State& y1) {
  const Eigen::Vector3d wind0 = wind_at(t0_s);
  const Eigen::Vector3d wind_mid = wind_at(t0_s + 0.5 * h_s);
  const Eigen::Vector3d& wind1 = wind_at(t0_s + h_s);
  State k1, k2, k3, k4, y;
  model_.derivatives(y0.data(), command_, wind0, on_ground_, k1.data());
  for (int i = 0; i < kStateSize; ++i) y[i] = y0[i] + 0.5 * h_s * k1[i];
  model_.derivatives(y.data(), command_, wind_mid, on_ground_, k2.data());
  for (int i = 0; i < kStateSize; ++i) y[i] = y0[i] + 0.5 * h_s * k2[i];
  model_.derivatives(y.data(), command_, wind_mid, on_ground_, k3.data());
  for (int i = 0; i < kStateSize; ++i) y[i] = y0[i] + h_s * k3[i];
  model_.derivatives(y.data(), command_, wind1, on_ground_, k4.data());
  const double sixth = h_s / 6.0;
  for (int i = 0; i < kStateSize; ++i) y1[i] = y0[i] + sixth * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  ++stats_.steps;
  stats_.rhs_evaluations += 4;
}

double Rk4Integrator::contact_function(const State& y) const {
  if (crashed_) return 1.0;
  if (!on_ground_) return y[index::kP + 2];  // touchdown when the altitude reaches 0
  RotorSpeeds speeds;
  for (int i = 0; i < 4; ++i) speeds[i] = y[index::kRotor + i];
  return model_.weight_N() - model_.total_thrust_N(speeds);  // lift-off when thrust reaches weight
}

double Rk4Integrator::battery_function(const State& y) const {
  return battery_empty_ ? 1.0 : model_.battery_energy_J() - y[index::kEnergy];
}

// The step length in (0, h_s] at which g reaches 0, from g(y_) > 0 and g(y1) <= 0; y_event is
// the state there (g <= 0).
double Rk4Integrator::locate_event(const State& y1, double h_s, double (Rk4Integrator::*g)(const State&) const,
                                   State& y_event) {
  double lo = 0.0, hi = h_s;
  double g_lo = (this->*g)(y_), g_hi = (this->*g)(y1);
  y_event = y1;
  int kept = 0;  // Illinois: which end was kept last (+1 lo, -1 hi)
  for (int i = 0; i < kMaxEventIterations && hi - lo > kEventTolerance_s; ++i) {
    double m = hi - g_hi * (hi - lo) / (g_hi - g_lo);
    if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
    State y_m;
    rk4_step(y_, time_s_, m, y_m);
    const double g_m = (this->*g)(y_m);
    if (g_m <= 0.0) {
      hi = m;
      g_hi = g_m;
      y_event = y_m;
      if (kept == +1) g_lo *= 0.5;
      kept = +1;
    } else {
      lo = m;
      g_lo = g_m;
      if (kept == -1) g_hi *= 0.5;
      kept = -1;
    }
  }
  return hi;
}

void Rk4Integrator::on_contact(double t_s) {
  ++stats_.events;
  state_ = unpack_state(y_.data());
  if (on_ground_) {
    liftoff(t_s, state_.p_W_m);
    state_.p_W_m.z() = std::max(state_.p_W_m.z(), kLiftoffHeight_m);
  } else {
    touchdown(t_s, state_.p_W_m, state_.v_W_mps.z());
    settle_on_ground();
    if (crashed_) {
      command_ = RotorSpeeds{};
    } else if (model_.total_thrust_N(state_.rotor_speed_radps) > model_.weight_N()) {
      // Touched down with more thrust than weight: it stays airborne, just above the floor.
      on_ground_ = false;
      state_.p_W_m.z() = kLiftoffHeight_m;
    }
  }
  pack_state(state_, y_.data());
}

void Rk4Integrator::on_battery_empty(double t_s) {
  ++stats_.events;
  state_ = unpack_state(y_.data());
  empty_battery(t_s);
  command_ = RotorSpeeds{};
}

// A vehicle on the ground whose thrust already exceeds its weight (after a reset or a landing
// under thrust) lifts off now: there is no sign change left to find.
void Rk4Integrator::lift_off_if_thrust_exceeds_weight() {
  if (on_ground_ && !crashed_ && contact_function(y_) < 0.0) on_contact(time_s_);
}

}  // namespace a3::dynamics
