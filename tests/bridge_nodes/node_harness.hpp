// Pieces for testing the fc and bridge nodes on their own in virtual time: a node that
// publishes a scripted vehicle state on A3_STATE, a DroneCAN "peer" on the virtual CAN bus
// that records what the node under test sends (by type, with receive times) and sends
// messages or raw frames of its own, and an LCM recorder.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "a3lcm/actuator_cmd_t.hpp"
#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "bridge/can/virtual_can_bus.hpp"
#include "bridge/dronecan/messages.hpp"
#include "bridge/dronecan/node.hpp"
#include "common/channels.hpp"
#include "common/runtime.hpp"

namespace a3::test {

// A vehicle at rest on the ground at the origin, unless state_at says otherwise.
inline a3lcm::vehicle_state_t resting_state(int64_t utime_us) {
  a3lcm::vehicle_state_t s{};
  s.utime_us = utime_us;
  s.q_WB[0] = 1.0;
  s.a_B_mps2[2] = 9.80665;
  s.battery_pct = 80.0;
  s.battery_voltage_v = 12.0;
  s.power_w = 5.0;
  s.mass_kg = 1.5;
  s.on_ground = true;
  return s;
}

class StatePublisher final : public common::Node {
 public:
  explicit StatePublisher(double rate_hz, std::function<a3lcm::vehicle_state_t(int64_t)> state_at = resting_state)
      : period_us_(std::llround(1e6 / rate_hz)), state_at_(std::move(state_at)) {}
  std::string name() const override { return "states"; }
  void start(common::Executor& executor, common::Bus& bus) override {
    executor.schedule(0, period_us_, [this, &executor, &bus] {
      if (enabled) bus.publish(common::channels::kState.of(0), state_at_(executor.clock().now_us()));
    });
  }
  bool enabled = true;

 private:
  int64_t period_us_;
  std::function<a3lcm::vehicle_state_t(int64_t)> state_at_;
};

// Records LCM traffic the nodes produce, and publishes commands.
class LcmRecorder final : public common::Node {
 public:
  std::string name() const override { return "lcm-recorder"; }
  void start(common::Executor&, common::Bus& bus) override {
    bus_ = &bus;
    bus.subscribe<a3lcm::actuator_cmd_t>(common::channels::kActuators.of(0),
                                         [this](const a3lcm::actuator_cmd_t& m, int64_t) { actuators.push_back(m); });
    bus.subscribe<a3lcm::fc_status_t>(common::channels::kFcStatus.of(0),
                                      [this](const a3lcm::fc_status_t& m, int64_t) { statuses.push_back(m); });
  }
  void command(const a3lcm::fc_command_t& c) { bus_->publish(common::channels::kFcCommand.of(0), c); }
  std::vector<a3lcm::actuator_cmd_t> actuators;
  std::vector<a3lcm::fc_status_t> statuses;

 private:
  common::Bus* bus_ = nullptr;
};

// Another DroneCAN node on the bus: what it received, by type, with receive times.
class CanPeer {
 public:
  template <class Msg>
  struct Received {
    Msg msg;
    int64_t t_us;
    uint8_t source;
  };

  CanPeer(bridge::VirtualCanBus& bus, uint8_t node_id)
      : port_(bus.attach("peer")), node_(*port_, bridge::DroneCanNodeConfig{node_id, {}, 500'000}) {}

  void start(common::Executor& executor) {
    executor_ = &executor;
    record(imu);
    record(gnss);
    record(baro);
    record(mag);
    record(battery);
    record(esc);
    record(commands);
    record(statuses);
    record(node_status);
    node_.start(executor);
  }
  template <class Msg>
  bool publish(const Msg& msg) { return node_.publish(msg); }
  bool send_raw(const bridge::CanFrame& f) { return port_->send(f); }
  bridge::DroneCanNode& node() { return node_; }

  std::vector<Received<bridge::AhrsRawImu>> imu;
  std::vector<Received<bridge::GnssFix2>> gnss;
  std::vector<Received<bridge::StaticPressure>> baro;
  std::vector<Received<bridge::MagneticFieldStrength2>> mag;
  std::vector<Received<bridge::BatteryInfo>> battery;
  std::vector<Received<bridge::EscRawCommand>> esc;
  std::vector<Received<bridge::FcCommand>> commands;
  std::vector<Received<bridge::FcStatus>> statuses;
  std::vector<Received<bridge::NodeStatus>> node_status;

 private:
  template <class Msg>
  void record(std::vector<Received<Msg>>& into) {
    node_.subscribe<Msg>([this, &into](const Msg& m, const bridge::ReceivedTransfer& t) {
      into.push_back({m, executor_->clock().now_us(), t.header.source_node_id});
    });
  }

  std::unique_ptr<bridge::CanBus> port_;
  bridge::DroneCanNode node_;
  common::Executor* executor_ = nullptr;
};

}  // namespace a3::test
