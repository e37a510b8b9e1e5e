// The LCM⇄CAN bridge node.
#include "bridge/sim/bridge_node.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "a3lcm/actuator_cmd_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/sim_clock_t.hpp"
#include "bridge/dronecan/messages.hpp"
#include "bridge/nodes/esc_scaling.hpp"
#include "bridge/nodes/fc_messages.hpp"
#include "bridge/sim/refusal_events.hpp"
#include "common/channels.hpp"
#include "common/log.hpp"
#include "common/text_format.hpp"

namespace a3::bridge {
namespace {

constexpr int64_t kNodeStatusPeriod_us = 1'000'000;
constexpr int64_t kRestartGap_us = 1'000'000;     // a state this far back: the dynamics restarted
constexpr double kPowerAverageTime_s = 10.0;      // BatteryInfo.average_power_10sec

using common::is_power_of_ten;


}  // namespace

BridgeNode::BridgeNode(CanBus& can, BridgeNodeConfig config)
    : config_(std::move(config)),
      frame_(config_.home),
      sensors_(config_.noise, config_.seed),
      dronecan_(can, DroneCanNodeConfig{config_.node_id, {}, 500'000}),
      imu_schedule_(config_.rates.imu_hz),
      gnss_schedule_(config_.rates.gnss_hz),
      baro_schedule_(config_.rates.baro_hz),
      temperature_schedule_(config_.rates.temperature_hz),
      mag_schedule_(config_.rates.mag_hz),
      battery_schedule_(config_.rates.battery_hz),
      foreign_refusals_(config_.refusal_report_interval_us, [this](uint64_t n, uint64_t total) {
        publish_safety(safety_event_from_foreign_fc_traffic(
            {last_foreign_source_, last_foreign_type_, config_.fc_node_id, n, total}, executor_->clock().now_us(),
            last_p_W_m_));
      }) {
  if (config_.fc_node_id < 1 || config_.fc_node_id > 127 || config_.fc_node_id == config_.node_id) {
    throw std::invalid_argument("bridge node: fc node ID " + std::to_string(config_.fc_node_id) +
                                " must be 1..127 and not the bridge's own (" + std::to_string(config_.node_id) + ")");
  }
  namespace ch = common::channels;
  const common::VehicleId v = config_.vehicle;
  channels_ = {ch::kState.of(v), ch::kActuators.of(v), ch::kFcCommand.of(v), ch::kFcStatus.of(v), ch::kSafety.of(v)};
}

std::optional<common::NodePorts> BridgeNode::ports() const {
  common::NodePorts ports;
  ports.subscribes(channels_.state).subscribes(channels_.command);
  if (config_.forward_sim_clock) ports.subscribes(common::channels::kClock);
  ports.publishes(channels_.actuators).publishes(channels_.status).publishes(channels_.safety);
  return ports;
}

BridgeNode::~BridgeNode() { stop(); }

void BridgeNode::warn(uint64_t count, const std::string& message) const {
  // The first, tenth, hundredth... occurrence: a flood of bad input stays readable.
  if (is_power_of_ten(count)) common::log_warn("bridge", message + " (" + std::to_string(count) + " so far)");
}

void BridgeNode::start(common::Executor& executor, common::Bus& bus) {
  if (executor_ != nullptr) throw std::logic_error("bridge node: started twice");
  executor_ = &executor;
  bus_ = &bus;
  foreign_refusals_.start(executor);
  dronecan_.subscribe<EscRawCommand>([this](const EscRawCommand& m, const ReceivedTransfer& t) {
    if (from_fc(t)) on_esc(m);
  });
  dronecan_.subscribe<FcStatus>([this](const FcStatus& m, const ReceivedTransfer& t) {
    if (from_fc(t)) on_status(m);
  });
  dronecan_.subscribe<FcCommandRefused>([this](const FcCommandRefused& m, const ReceivedTransfer& t) {
    if (from_fc(t)) on_fc_refusal(m);
  });
  dronecan_.publish_node_status_every(kNodeStatusPeriod_us);
  dronecan_.start(executor);
  bus.subscribe<a3lcm::vehicle_state_t>(channels_.state,
                                        [this](const a3lcm::vehicle_state_t& s, int64_t) { on_state(s); });
  bus.subscribe<a3lcm::fc_command_t>(channels_.command,
                                     [this](const a3lcm::fc_command_t& c, int64_t) { on_command(c); });
  if (config_.forward_sim_clock) {
    // A later round of a time is for the ground's followers; the flight controller has it already.
    bus.subscribe<a3lcm::sim_clock_t>(common::channels::kClock, [this](const a3lcm::sim_clock_t& m, int64_t) {
      if (m.round == 0) on_grant(m.utime_us);
    });
  }
  timers_.push_back(executor.schedule_every(kNodeStatusPeriod_us / 2, [this] { update_health(); }));
  common::log_info("bridge", "node " + std::to_string(config_.node_id) + " on " + dronecan_.bus().name() +
                                 ": IMU " + std::to_string(config_.rates.imu_hz) + " Hz (at most one per state)");
}

void BridgeNode::stop() {
  if (executor_ == nullptr) return;
  for (const auto id : timers_) executor_->cancel(id);
  timers_.clear();
  foreign_refusals_.stop();
  dronecan_.stop();
  executor_ = nullptr;
}

template <class Msg>
void BridgeNode::publish_can(const Msg& msg, uint8_t priority) {
  if (!dronecan_.publish(msg, priority)) ++counters_.can_publish_failures;
}

void BridgeNode::on_state(const a3lcm::vehicle_state_t& s) {
  if (!vehicle_state_is_valid(s)) {
    warn(++counters_.states_rejected, "dropped a vehicle state with NaN, infinite or non-unit-attitude values");
    return;
  }
  if (have_state_ && s.utime_us <= last_state_utime_us_) {
    if (last_state_utime_us_ - s.utime_us < kRestartGap_us) {
      warn(++counters_.states_rejected, "dropped a vehicle state older than the last one");
      return;
    }
    common::log_info("bridge", "vehicle state time went back by more than 1 s: the sensors start over");
    imu_.reset();
    for (RateSchedule* r : {&imu_schedule_, &gnss_schedule_, &baro_schedule_, &temperature_schedule_,
                            &mag_schedule_, &battery_schedule_}) {
      r->reset();
    }
    have_power_ = false;
  }
  const double dt_s = have_state_ ? static_cast<double>(s.utime_us - last_state_utime_us_) * 1e-6 : 0.0;
  have_state_ = true;
  last_state_utime_us_ = s.utime_us;
  last_state_rx_us_ = executor_->clock().now_us();
  for (int i = 0; i < 3; ++i) last_p_W_m_[i] = s.p_W_m[i];
  ++counters_.states;
  if (!have_power_) {
    average_power_W_ = s.power_w;
    have_power_ = true;
  } else {
    const double alpha = std::clamp(dt_s / kPowerAverageTime_s, 0.0, 1.0);
    average_power_W_ += alpha * (s.power_w - average_power_W_);
  }
  publish_sensors(s);
}

void BridgeNode::publish_sensors(const a3lcm::vehicle_state_t& s) {
  const TruthSample truth = truth_from_state(s);
  const uint64_t stamp_us = static_cast<uint64_t>(std::max<int64_t>(s.utime_us, 0));
  imu_.add(truth.t_s, sensors_.gyro_B_radps(truth), sensors_.accel_B_mps2(truth));
  if (imu_schedule_.due(s.utime_us)) {
    publish_can(imu_.take_report(stamp_us), kPriorityHigh);
    ++counters_.imu;
  }
  if (gnss_schedule_.due(s.utime_us)) {
    const Eigen::Vector3d p = sensors_.gnss_position_W_m(truth);
    const Eigen::Vector3d v = sensors_.gnss_velocity_W_mps(truth);
    publish_can(make_gnss_fix(stamp_us, frame_, p, v), kPriorityMedium);
    ++counters_.gnss;
  }
  if (baro_schedule_.due(s.utime_us)) {
    const double pressure = sensors_.static_pressure_Pa(truth, config_.home.height_m);
    publish_can(make_static_pressure(pressure, sensors_.noise().baro_pressure_Pa), kPriorityMedium);
    ++counters_.baro;
  }
  if (temperature_schedule_.due(s.utime_us)) {
    publish_can(make_static_temperature(isa_temperature_K(config_.home.height_m + truth.p_W_m.z())),
                kPriorityLow);
  }
  if (mag_schedule_.due(s.utime_us)) {
    publish_can(make_magnetic_field(sensors_.magnetic_field_B_gauss(truth), sensors_.noise().mag_gauss),
                kPriorityMedium);
    ++counters_.mag;
  }
  if (battery_schedule_.due(s.utime_us)) {
    publish_can(make_battery_info(s, average_power_W_), kPriorityLow);
    ++counters_.battery;
  }
}

void BridgeNode::on_command(const a3lcm::fc_command_t& c) {
  ++counters_.commands;
  if (fc_command_has_nonfinite(c)) {
    warn(++counters_.commands_nonfinite,
         "forwarding a command with a non-finite target or speed (seq " + std::to_string(c.seq) +
             "): the fc will refuse it");
  }
  publish_can(fc_command_to_can(c), kPriorityMedium);
}

void BridgeNode::on_esc(const EscRawCommand& esc) {
  if (esc.cmd.size() < 4) {
    warn(++counters_.esc_rejected, "dropped an esc.RawCommand for " + std::to_string(esc.cmd.size()) +
                                       " rotors (the quadrotor needs 4)");
    return;
  }
  a3lcm::actuator_cmd_t out;
  out.utime_us = executor_->clock().now_us();
  out.armed = false;
  bool clamped = false;
  for (int i = 0; i < 4; ++i) {
    clamped |= esc.cmd[i] < 0;
    out.throttle[i] = esc_raw_to_throttle(esc.cmd[i]);
    out.armed |= esc.cmd[i] > 0;
  }
  if (clamped) warn(++counters_.esc_clamped, "took a reverse (negative) esc.RawCommand as 0");
  ++counters_.esc_frames;
  bus_->publish(channels_.actuators, out);
  last_actuator_ = out;
  have_actuator_ = true;
}

void BridgeNode::on_grant(int64_t utime_us) {
  // The runtime's own subscription has moved this node's clock already; the sensor frames of
  // this time went out when its state came (the state precedes its grant on the bus).
  ++counters_.clock_grants;
  SimClock clock;
  clock.utime_us = static_cast<uint64_t>(std::max<int64_t>(utime_us, 0));
  publish_can(clock, kPriorityHigh);
  if (utime_us == last_grant_us_ && have_actuator_) bus_->publish(channels_.actuators, last_actuator_);
  last_grant_us_ = utime_us;
}

void BridgeNode::on_status(const FcStatus& status) {
  ++counters_.statuses;
  bus_->publish(channels_.status, fc_status_from_can(status, executor_->clock().now_us()));
}

bool BridgeNode::from_fc(const ReceivedTransfer& t) {
  if (t.header.source_node_id == config_.fc_node_id) return true;
  last_foreign_source_ = t.header.source_node_id;
  last_foreign_type_ = t.header.data_type_id;
  warn(++counters_.rejected_source, "refused " + data_type_text(t.header.data_type_id) + " from CAN node " +
                                        std::to_string(t.header.source_node_id) + ": not the fc (node " +
                                        std::to_string(config_.fc_node_id) + ")");
  foreign_refusals_.record();
  return false;
}

void BridgeNode::on_fc_refusal(const FcCommandRefused& report) {
  publish_safety(safety_event_from_fc_refusal(report, executor_->clock().now_us(), last_p_W_m_));
}

void BridgeNode::publish_safety(const a3lcm::safety_event_t& event) {
  ++counters_.refusal_events;
  bus_->publish(channels_.safety, event);
}

void BridgeNode::update_health() {
  const int64_t now_us = executor_->clock().now_us();
  const bool stale = last_state_rx_us_ < 0 || now_us - last_state_rx_us_ > config_.state_timeout_us;
  dronecan_.set_health(stale ? NodeStatus::kHealthWarning : NodeStatus::kHealthOk);
}


}  // namespace a3::bridge
