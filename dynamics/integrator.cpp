// The integrator interface and the bookkeeping the integrators share.
#include "dynamics/integrator.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <stdexcept>

#include "dynamics/cvode_integrator.hpp"
#include "dynamics/ode_integrator.hpp"
#include "dynamics/rk4_integrator.hpp"

namespace a3::dynamics {

const char* to_string(DynamicsEvent::Kind kind) {
  switch (kind) {
    case DynamicsEvent::Kind::kTouchdown: return "touchdown";
    case DynamicsEvent::Kind::kLiftoff: return "liftoff";
    case DynamicsEvent::Kind::kCrash: return "crash";
    case DynamicsEvent::Kind::kBatteryEmpty: return "battery_empty";
  }
  return "unknown";
}

Integrator::Integrator(const QuadrotorModel& model, WindField& wind) : model_(model), wind_(wind) {}

void Integrator::reset(const VehicleState& s, double t_s) {
  state_ = s;
  state_.q_WB.normalize();
  time_s_ = t_s;
  crashed_ = false;
  battery_empty_ = s.energy_used_J >= model_.battery_energy_J();
  on_ground_ = state_.p_W_m.z() <= 0.0;
  if (on_ground_) {
    state_.p_W_m.z() = 0.0;
    state_.v_W_mps.setZero();
    state_.w_B_radps.setZero();
  }
  events_.clear();
  on_reset();
}

void Integrator::advance_to(double t_end_s, const RotorSpeeds& command_radps) {
  if (!(t_end_s > time_s_)) return;
  integrate(t_end_s, effective_command(command_radps));
}

RotorSpeeds Integrator::effective_command(const RotorSpeeds& command) const {
  if (crashed_ || battery_empty_) return RotorSpeeds{};
  RotorSpeeds out;
  const double max = model_.params().rotor.max_speed_radps;
  for (int i = 0; i < 4; ++i) out[i] = std::clamp(command[i], 0.0, max);
  return out;
}

std::vector<DynamicsEvent> Integrator::take_events() {
  std::vector<DynamicsEvent> out;
  out.swap(events_);
  return out;
}

void Integrator::touchdown(double t_s, const Eigen::Vector3d& p_W_m, double vertical_speed_mps) {
  const bool crash = -vertical_speed_mps > model_.params().crash_speed_mps;
  events_.push_back({crash ? DynamicsEvent::Kind::kCrash : DynamicsEvent::Kind::kTouchdown, t_s,
                     p_W_m, vertical_speed_mps});
  if (crash) crashed_ = true;
  on_ground_ = true;
}

void Integrator::liftoff(double t_s, const Eigen::Vector3d& p_W_m) {
  events_.push_back({DynamicsEvent::Kind::kLiftoff, t_s, p_W_m, 0.0});
  on_ground_ = false;
}

void Integrator::empty_battery(double t_s) {
  if (battery_empty_) return;
  battery_empty_ = true;
  events_.push_back({DynamicsEvent::Kind::kBatteryEmpty, t_s, state_.p_W_m, state_.v_W_mps.z()});
}

void Integrator::settle_on_ground() {
  const double yaw = roll_pitch_yaw_rad(state_.q_WB).z();
  state_.p_W_m.z() = 0.0;
  state_.v_W_mps.setZero();
  state_.w_B_radps.setZero();
  state_.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
}

IntegratorKind parse_integrator_kind(const std::string& name) {
  for (IntegratorKind kind : kAllIntegrators) {
    if (name == to_string(kind)) return kind;
  }
  throw std::invalid_argument("unknown integrator '" + name + "' (known: rk4, cvode, ode)");
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (IntegratorKind kind : kAllIntegrators) names.emplace_back(to_string(kind));
  return names;
}

std::map<std::string, IntegratorKind> integrator_by_name() {
  std::map<std::string, IntegratorKind> out;
  for (IntegratorKind kind : kAllIntegrators) out.emplace(to_string(kind), kind);
  return out;
}

const char* to_string(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::kRk4: return "rk4";
    case IntegratorKind::kCvode: return "cvode";
    case IntegratorKind::kOde: return "ode";
  }
  return "unknown";
}

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind, const QuadrotorModel& model,
                                            WindField& wind, const IntegratorOptions& options) {
  switch (kind) {
    case IntegratorKind::kRk4: return std::make_unique<Rk4Integrator>(model, wind, options.rk4_max_step_s);
    case IntegratorKind::kOde: return std::make_unique<OdeIntegrator>(model, wind, options.ode_step_s);
    case IntegratorKind::kCvode: break;
  }
  return std::make_unique<CvodeIntegrator>(model, wind, options.relative_tolerance);
}

}  // namespace a3::dynamics
