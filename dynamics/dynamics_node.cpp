// The dynamics node.
#include "dynamics/dynamics_node.hpp"

#include <cmath>
#include <stdexcept>

#include "a3lcm/safety_event_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/channels.hpp"
#include "common/log.hpp"
#include "dynamics/battery.hpp"
#include "common/text_format.hpp"

namespace a3::dynamics {
namespace {

using common::is_power_of_ten;

}  // namespace

DynamicsNode::DynamicsNode(DynamicsNodeConfig config) : config_(std::move(config)) {
  if (!(config_.publish_rate_hz > 0.0 && config_.publish_rate_hz <= 10000.0)) {
    throw std::invalid_argument("dynamics: publish rate must be in (0, 10000] Hz, got " +
                                std::to_string(config_.publish_rate_hz));
  }
  if (!(config_.command_timeout_s > 0.0)) {
    throw std::invalid_argument("dynamics: command timeout must be > 0 s, got " +
                                std::to_string(config_.command_timeout_s));
  }
  period_us_ = static_cast<int64_t>(std::llround(1e6 / config_.publish_rate_hz));
  state_channel_ = common::channels::kState.of(config_.vehicle);
  model_ = std::make_unique<QuadrotorModel>(config_.params);
  wind_ = std::make_unique<WindField>(config_.mean_wind_W_mps, config_.turbulence, config_.seed);
  integrator_ = make_integrator(config_.integrator, *model_, *wind_, config_.integrator_options);
}

DynamicsNode::~DynamicsNode() = default;

std::optional<common::NodePorts> DynamicsNode::ports() const {
  const common::VehicleId v = config_.vehicle;
  return common::NodePorts()
      .subscribes(common::channels::kActuators.of(v))
      .publishes(common::channels::kState.of(v))
      .publishes(common::channels::kSafety.of(v));
}


void DynamicsNode::start(common::Executor& executor, common::Bus& bus) {
  executor_ = &executor;
  bus_ = &bus;
  const int64_t now_us = executor.clock().now_us();
  start_us_ = (now_us + period_us_ - 1) / period_us_ * period_us_;
  step_index_ = 0;
  integrator_->reset(config_.initial_state, start_us_ * 1e-6);
  command_radps_ = config_.initial_state.rotor_speed_radps;
  last_command_us_ = start_us_;
  bus.subscribe(
      common::channels::kActuators.of(config_.vehicle),
      [this](const a3lcm::actuator_cmd_t& cmd, int64_t recv_us) { on_command(cmd, recv_us); });
  executor.schedule_at(start_us_, [this] { publish_state(start_us_); });
  executor.schedule(start_us_ + period_us_, period_us_, [this] { step(); });
}

void DynamicsNode::warn(uint64_t count, const std::string& message) const {
  // The first, tenth, hundredth... occurrence: a flood of bad commands stays readable.
  if (is_power_of_ten(count)) {
    common::log_warn("dynamics", message + " (" + std::to_string(count) + " so far)");
  }
}

void DynamicsNode::on_command(const a3lcm::actuator_cmd_t& cmd, int64_t recv_utime_us) {
  ++counters_.commands_received;
  for (double throttle : cmd.throttle) {
    if (!std::isfinite(throttle)) {
      warn(++counters_.commands_rejected, "rejected an actuator command with a non-finite throttle");
      return;
    }
  }
  bool clamped = false;
  RotorSpeeds speeds{};
  for (int i = 0; i < 4; ++i) {
    const double throttle = cmd.throttle[i];
    clamped |= throttle < 0.0 || throttle > 1.0;
    speeds[i] = cmd.armed ? model_->throttle_to_speed_radps(throttle) : 0.0;
  }
  if (clamped) {
    warn(++counters_.commands_clamped, "clamped an actuator command with a throttle outside [0, 1]");
  }
  command_radps_ = speeds;
  last_command_us_ = recv_utime_us;
}

void DynamicsNode::step() {
  // The grid time of this step, not the (possibly late) wall time: both runtimes integrate the
  // same intervals.
  ++step_index_;
  const int64_t t_us = start_us_ + static_cast<int64_t>(step_index_) * period_us_;
  const bool stale = !last_command_us_ ||
                     t_us - *last_command_us_ > static_cast<int64_t>(config_.command_timeout_s * 1e6);
  if (stale) ++counters_.stale_steps;
  if (stale && !was_stale_) publish_command_timeout(t_us);
  was_stale_ = stale;
  const RotorSpeeds command = stale ? RotorSpeeds{} : command_radps_;
  try {
    integrator_->advance_to(t_us * 1e-6, command);
  } catch (const std::exception& e) {
    warn(++counters_.integration_errors, std::string("integration failed: ") + e.what());
  }
  ++counters_.steps;
  publish_events(t_us);
  publish_state(t_us);
}

void DynamicsNode::publish_events(int64_t utime_us) {
  for (const DynamicsEvent& e : integrator_->take_events()) {
    if (e.kind == DynamicsEvent::Kind::kCrash) {
      a3lcm::safety_event_t ev;
      ev.utime_us = utime_us;
      ev.kind = "crash";
      ev.source = "dynamics";
      for (int i = 0; i < 3; ++i) ev.p_W_m[i] = e.p_W_m[i];
      ev.value = e.vertical_speed_mps;
      ev.detail = "ground impact at " + std::to_string(-e.vertical_speed_mps) + " m/s";
      bus_->publish(common::channels::kSafety.of(config_.vehicle), ev);
      common::log_warn("dynamics", ev.detail);
    } else {
      common::log_info("dynamics", std::string(to_string(e.kind)) + " at t=" + std::to_string(e.time_s) + " s");
    }
  }
}

void DynamicsNode::publish_command_timeout(int64_t utime_us) {
  const VehicleState& s = integrator_->state();
  a3lcm::safety_event_t ev;
  ev.utime_us = utime_us;
  ev.kind = "command_timeout";
  ev.source = "dynamics";
  for (int i = 0; i < 3; ++i) ev.p_W_m[i] = s.p_W_m[i];
  ev.value = last_command_us_ ? (utime_us - *last_command_us_) * 1e-6 : 0.0;
  ev.detail = "no rotor command for " + std::to_string(ev.value) + " s of simulated time: motors spun down";
  bus_->publish(common::channels::kSafety.of(config_.vehicle), ev);
  common::log_warn("dynamics", ev.detail);
}

void DynamicsNode::publish_state(int64_t utime_us) {
  const VehicleState& s = integrator_->state();
  const Eigen::Vector3d wind = wind_->wind_W_mps(utime_us * 1e-6);
  const double power_W = model_->electrical_power_W(s.rotor_speed_radps);
  const BatteryReading battery =
      read_battery(model_->params().battery, model_->battery_energy_J(), s.energy_used_J, power_W);
  const Eigen::Vector3d f_B = integrator_->on_ground()
                                  ? Eigen::Vector3d(s.q_WB.conjugate() * Eigen::Vector3d(0, 0, kGravity_mps2))
                                  : model_->specific_force_B_mps2(s, wind);
  a3lcm::vehicle_state_t msg;
  msg.utime_us = utime_us;
  for (int i = 0; i < 3; ++i) {
    msg.p_W_m[i] = s.p_W_m[i];
    msg.v_W_mps[i] = s.v_W_mps[i];
    msg.w_B_radps[i] = s.w_B_radps[i];
    msg.a_B_mps2[i] = f_B[i];
    msg.wind_W_mps[i] = wind[i];
  }
  msg.q_WB[0] = s.q_WB.w();
  msg.q_WB[1] = s.q_WB.x();
  msg.q_WB[2] = s.q_WB.y();
  msg.q_WB[3] = s.q_WB.z();
  for (int i = 0; i < 4; ++i) msg.rotor_speed_radps[i] = s.rotor_speed_radps[i];
  msg.battery_pct = battery.percent;
  msg.battery_voltage_v = battery.voltage_V;
  msg.power_w = power_W;
  msg.mass_kg = model_->mass_kg();
  msg.on_ground = integrator_->on_ground();
  msg.crashed = integrator_->crashed();
  bus_->publish(state_channel_, msg);
}

}  // namespace a3::dynamics
