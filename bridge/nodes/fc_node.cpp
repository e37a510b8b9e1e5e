// The fc node: CAN sensors and commands in, ESC commands and status out.
#include "bridge/nodes/fc_node.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bridge/dronecan/messages.hpp"
#include "bridge/nodes/esc_scaling.hpp"
#include "bridge/nodes/fc_messages.hpp"
#include "bridge/nodes/sensor_readings.hpp"
#include "common/log.hpp"
#include "common/text_format.hpp"

namespace a3::bridge {
namespace {

constexpr int64_t kNodeStatusPeriod_us = 1'000'000;

int64_t period_us_of(double rate_hz, const char* what) {
  if (!(rate_hz > 0.0 && rate_hz <= 10000.0)) {
    throw std::invalid_argument(std::string("fc node: ") + what + " must be in (0, 10000] Hz, got " +
                                std::to_string(rate_hz));
  }
  return std::llround(1e6 / rate_hz);
}

using common::is_power_of_ten;

}  // namespace

FcNode::FcNode(CanBus& can, FcNodeConfig config)
    : config_(std::move(config)),
      frame_(config_.home),
      fc_(config_.params, config_.estimator_noise),
      dronecan_(can, DroneCanNodeConfig{config_.node_id, {}, 500'000}),
      refusals_(config_.refusal_report_interval_us, [this](uint64_t n, uint64_t total) { report_refusals(n, total); }) {
  check_command_sources(config_.command_sources, config_.node_id);
  period_us_of(config_.params.control_rate_hz, "control_rate_hz");
  period_us_of(config_.params.status_rate_hz, "status_rate_hz");
  status_copy_ = fc_.status();
}

FcNode::~FcNode() { stop(); }

double FcNode::now_s() const { return executor_->clock().now_s(); }

void FcNode::reject(const char* what) {
  const uint64_t n = ++counters_.sensor_rejected;
  if (is_power_of_ten(n)) {
    common::log_warn("fc", std::string("dropped an unusable ") + what + " message (" + std::to_string(n) +
                               " sensor messages dropped so far)");
  }
}

double FcNode::imu_time_s(double rx_s, double interval_s) {
  // Frames that queued up (a busy bus, a descheduled process) arrive together: their receive
  // times say nothing of when they were sampled, their integration intervals do. The estimator
  // only takes differences of these times, so they may run apart from the node's clock.
  if (imu_time_s_ < 0.0) {
    imu_time_s_ = rx_s;
  } else if (interval_s > 0.0) {
    imu_time_s_ += interval_s;
  } else {
    imu_time_s_ += std::max(rx_s - last_imu_rx_s_, 0.0);
  }
  last_imu_rx_s_ = rx_s;
  return imu_time_s_;
}

void FcNode::subscribe_sensors() {
  dronecan_.subscribe<AhrsRawImu>([this](const AhrsRawImu& m, const ReceivedTransfer&) {
    const auto r = imu_reading(m);
    if (!r) return reject("ahrs.RawIMU");
    ++counters_.imu;
    last_imu_us_ = executor_->clock().now_us();
    fc_.estimator().on_imu(imu_time_s(now_s(), r->from_integral ? m.integration_interval : 0.0), r->gyro_B_radps,
                           r->accel_B_mps2);
  });
  dronecan_.subscribe<GnssFix2>([this](const GnssFix2& m, const ReceivedTransfer&) {
    const auto r = gnss_reading(m, frame_);
    if (!r) return reject("gnss.Fix2");
    ++counters_.gnss;
    last_gnss_us_ = executor_->clock().now_us();
    fc_.estimator().on_gnss(now_s(), r->p_W_m, r->v_W_mps);
  });
  dronecan_.subscribe<StaticPressure>([this](const StaticPressure& m, const ReceivedTransfer&) {
    const auto altitude = baro_altitude_m(m, config_.home.height_m);
    if (!altitude) return reject("air_data.StaticPressure");
    ++counters_.baro;
    last_baro_us_ = executor_->clock().now_us();
    fc_.estimator().on_baro(now_s(), *altitude);
  });
  dronecan_.subscribe<MagneticFieldStrength2>([this](const MagneticFieldStrength2& m, const ReceivedTransfer&) {
    const auto field = magnetic_field_B(m);
    if (!field) return reject("ahrs.MagneticFieldStrength2");
    ++counters_.mag;
    fc_.estimator().on_magnetometer(now_s(), *field);
  });
  dronecan_.subscribe<BatteryInfo>([this](const BatteryInfo& m, const ReceivedTransfer&) {
    const auto percent = battery_percent(m);
    if (!percent) return reject("power.BatteryInfo");
    ++counters_.battery;
    fc_.on_battery(now_s(), *percent);
  });
}

void FcNode::start(common::Executor& executor, common::Bus&) {
  if (executor_ != nullptr) throw std::logic_error("fc node: started twice");
  executor_ = &executor;
  refusals_.start(executor);
  subscribe_sensors();
  dronecan_.subscribe<FcCommand>([this](const FcCommand& c, const ReceivedTransfer& t) {
    const uint8_t source = t.header.source_node_id;
    if (!is_command_source(config_.command_sources, source)) {
      return refuse_source(source, FcCommand::kType.default_dtid, c.command, c.seq);
    }
    on_command(c);
  });
  if (sim_clock_ != nullptr) {
    dronecan_.subscribe<SimClock>([this](const SimClock& m, const ReceivedTransfer& t) {
      const uint8_t source = t.header.source_node_id;
      if (!is_command_source(config_.command_sources, source)) {
        return refuse_source(source, SimClock::kType.default_dtid, 0, 0);
      }
      ++counters_.clock_grants;
      sim_clock_->advance_to(static_cast<int64_t>(m.utime_us));
    });
  }
  dronecan_.publish_node_status_every(kNodeStatusPeriod_us);
  dronecan_.set_mode(NodeStatus::kModeInitialization);
  dronecan_.start(executor);

  const int64_t now_us = executor.clock().now_us();
  const int64_t control_us = period_us_of(config_.params.control_rate_hz, "control_rate_hz");
  const int64_t status_us = period_us_of(config_.params.status_rate_hz, "status_rate_hz");
  // On the grid of whole periods, as the dynamics node steps.
  const int64_t first_step_us = (now_us / control_us + 1) * control_us;
  timers_.push_back(executor.schedule(first_step_us, control_us, [this] { step(); }));
  timers_.push_back(executor.schedule((now_us / status_us + 1) * status_us, status_us, [this] {
    update_health();
    publish_status();
  }));
  common::log_info("fc", "node " + std::to_string(config_.node_id) + " on " + dronecan_.bus().name() + ": control " +
                             std::to_string(config_.params.control_rate_hz) + " Hz, status " +
                             std::to_string(config_.params.status_rate_hz) + " Hz, commands from node(s) " +
                             command_sources_text(config_.command_sources));
}

void FcNode::stop() {
  if (executor_ == nullptr) return;
  for (const auto id : timers_) executor_->cancel(id);
  timers_.clear();
  refusals_.stop();
  dronecan_.stop();
  executor_ = nullptr;
}

void FcNode::on_command(const FcCommand& c) {
  ++counters_.commands;
  const bool heartbeat = c.command == FcCommand::kHeartbeat;
  if (!heartbeat && have_command_seq_ && c.seq == last_command_seq_) {
    // A retransmission: keeps the link alive, changes nothing, gets its status again.
    ++counters_.commands_repeated;
    fc_.on_command(FlightCommand{}, now_s());
    executor_->schedule_at(executor_->clock().now_us(), [this] { publish_status(); });
    return;
  }
  const FlightCommandResult result = fc_.on_command(flight_command_from_can(c), now_s());
  if (heartbeat) {
    ++counters_.heartbeats;
    return;
  }
  have_command_seq_ = true;
  last_command_seq_ = c.seq;
  if (!result.accepted) {
    ++counters_.commands_refused;
    common::log_info("fc", "refused command " + std::to_string(c.command) + " (seq " + std::to_string(c.seq) +
                               "): " + result.reason);
  }
  // The reply goes out as its own event at this same instant, not from inside the CAN receive
  // callback: VirtualCanBus starts a second frame on the wire when a frame is queued from a
  // receive handler (reported), which reorders frames.
  const bool run_step = result.accepted && config_.step_on_command;
  executor_->schedule_at(executor_->clock().now_us(), [this, run_step] {
    if (run_step) step();
    publish_status();
  });
}

void FcNode::refuse_source(uint8_t source_node_id, uint16_t data_type_id, uint8_t command, int32_t seq) {
  const uint64_t n = ++counters_.commands_rejected_source;
  if (is_power_of_ten(n)) {
    common::log_warn("fc", "refused data type " + std::to_string(data_type_id) + " (command " +
                               std::to_string(command) + ") from node " + std::to_string(source_node_id) +
                               ": not a command source (" + command_sources_text(config_.command_sources) + "); " +
                               std::to_string(n) + " refused so far");
  }
  last_refused_.source_node_id = source_node_id;
  last_refused_.data_type_id = data_type_id;
  last_refused_.command = command;
  last_refused_.seq = seq;
  refusals_.record();
}

void FcNode::report_refusals(uint64_t refused_in_report, uint64_t refused_total) {
  FcCommandRefused report = last_refused_;
  report.refused_in_report = static_cast<uint16_t>(std::min<uint64_t>(refused_in_report, UINT16_MAX));
  report.refused_total = static_cast<uint32_t>(std::min<uint64_t>(refused_total, UINT32_MAX));
  if (dronecan_.publish(report)) ++counters_.refusal_reports;
}

void FcNode::step() {
  ++counters_.steps;
  const FcOutput out = fc_.step(now_s());
  EscRawCommand esc;
  for (int i = 0; i < 4; ++i) esc.cmd.push_back(out.armed ? throttle_to_esc_raw(out.throttle[i]) : int16_t{0});
  if (dronecan_.publish(esc, kPriorityHigh)) ++counters_.esc_published;
}

void FcNode::publish_status() {
  const FlightStatus& s = fc_.status();
  if (dronecan_.publish(fc_status_to_can(s))) ++counters_.status_published;
  std::lock_guard<std::mutex> lock(status_mutex_);
  status_copy_ = s;
}

void FcNode::update_health() {
  const FlightStatus& s = fc_.status();
  const int64_t now_us = executor_->clock().now_us();
  const auto silent = [&](int64_t last_us) { return last_us < 0 || now_us - last_us > config_.sensor_timeout_us; };
  uint8_t health = NodeStatus::kHealthOk;
  if (s.failsafe == FcFailsafe::kLinkLoss || s.failsafe == FcFailsafe::kGeofence ||
      s.failsafe == FcFailsafe::kAltitude || silent(last_imu_us_) || silent(last_baro_us_) ||
      now_us - last_gnss_us_ > 5 * config_.sensor_timeout_us) {
    health = NodeStatus::kHealthWarning;
  }
  if (s.failsafe == FcFailsafe::kLowBattery) health = NodeStatus::kHealthError;
  if (s.mode == FcMode::kEmergency) health = NodeStatus::kHealthCritical;
  dronecan_.set_health(health);
  dronecan_.set_mode(fc_.estimator().state().valid() ? NodeStatus::kModeOperational
                                                      : NodeStatus::kModeInitialization);
  // Vendor status: the fc mode in the high byte, the failsafe in the low byte.
  dronecan_.set_vendor_status(static_cast<uint16_t>((static_cast<unsigned>(s.mode) << 8) |
                                                    static_cast<unsigned>(s.failsafe)));
}


FlightStatus FcNode::status_snapshot() const {
  std::lock_guard<std::mutex> lock(status_mutex_);
  return status_copy_;
}

}  // namespace a3::bridge
