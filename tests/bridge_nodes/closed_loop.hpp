// The full closed loop in virtual time, as the rig runs it: the dynamics node (CVODE, 250 Hz)
// and the bridge node on the virtual LCM bus, the bridge and the fc node on one VirtualCanBus
// (1 Mbit/s, arbitration, wire time), and a ground station that publishes A3_FC_CMD (commands
// and 5 Hz heartbeats) and records A3_FC_STATUS and A3_STATE. The test sees the vehicle only
// as the ground would: through LCM.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "bridge/can/virtual_can_bus.hpp"
#include "bridge/nodes/fc_node.hpp"
#include "bridge/sim/bridge_node.hpp"
#include "common/channels.hpp"
#include "common/runtime.hpp"
#include "dynamics/dynamics_node.hpp"
#include "dynamics/quadrotor_model.hpp"
#include "rigs/run/fc_setup.hpp"

namespace a3::test {

// The ground side: commands with increasing seq, heartbeats while enabled, and what comes back.
class GroundStation final : public common::Node {
 public:
  explicit GroundStation(common::VehicleId vehicle = 0) : vehicle_(vehicle) {}
  std::string name() const override { return vehicle_ == 0 ? "ground" : "ground_v" + std::to_string(vehicle_); }
  void start(common::Executor& executor, common::Bus& bus) override {
    executor_ = &executor;
    bus_ = &bus;
    bus.subscribe<a3lcm::fc_status_t>(common::channels::kFcStatus.of(vehicle_), [this](const a3lcm::fc_status_t& s, int64_t) {
      statuses.push_back(s);
      max_failsafe_seen = std::max<int>(max_failsafe_seen, s.failsafe);
      if (on_status) on_status(s);
    });
    bus.subscribe<a3lcm::vehicle_state_t>(common::channels::kState.of(vehicle_), [this](const a3lcm::vehicle_state_t& s, int64_t) {
      state = s;
      ++states;
      if (on_state) on_state(s);
    });
    executor.schedule_every(200'000, [this] {
      if (heartbeats) send(a3lcm::fc_command_t::HEARTBEAT, seq_);
    });
  }

  // Publishes a command; returns its seq.
  int32_t command(int8_t kind, double x = 0, double y = 0, double z = 0, double speed_mps = 0,
                  double yaw_deg = std::nan("")) {
    send(kind, ++seq_, x, y, z, speed_mps, yaw_deg);
    return seq_;
  }
  const a3lcm::fc_status_t* status_for(int32_t seq) const {
    for (auto it = statuses.rbegin(); it != statuses.rend(); ++it) {
      if (it->last_command_seq == seq) return &*it;
    }
    return nullptr;
  }
  const a3lcm::fc_status_t& last_status() const { return statuses.back(); }

  bool heartbeats = true;
  std::vector<a3lcm::fc_status_t> statuses;
  int max_failsafe_seen = 0;
  a3lcm::vehicle_state_t state{};
  uint64_t states = 0;
  std::function<void(const a3lcm::vehicle_state_t&)> on_state;
  std::function<void(const a3lcm::fc_status_t&)> on_status;

 private:
  void send(int8_t kind, int32_t seq, double x = 0, double y = 0, double z = 0, double speed_mps = 0,
            double yaw_deg = std::nan("")) {
    a3lcm::fc_command_t c{};
    c.utime_us = executor_->clock().now_us();
    c.seq = seq;
    c.command = kind;
    c.target_W_m[0] = x;
    c.target_W_m[1] = y;
    c.target_W_m[2] = z;
    c.speed_limit_mps = speed_mps;
    c.yaw_deg = yaw_deg;
    bus_->publish(common::channels::kFcCommand.of(vehicle_), c);
  }

  common::VehicleId vehicle_ = 0;
  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  int32_t seq_ = 0;
};

struct LoopOptions {
  std::string airframe;  // built-in name or file; "" = the default (Iris)
  Eigen::Vector3d mean_wind_W_mps = Eigen::Vector3d::Zero();
  bool turbulence = false;
  uint64_t seed = 1;
  double dynamics_rate_hz = 250.0;
  double initial_battery_pct = 100.0;
  bridge::Geofence fence;
  std::function<void(bridge::FcParams&)> tune;  // changes to the fc's parameters
};

class ClosedLoop {
 public:
  explicit ClosedLoop(const LoopOptions& o = {})
      : can_(rt_.scheduler()), fc_port_(can_.attach("fc")), bridge_port_(can_.attach("bridge")) {
    dynamics::DynamicsNodeConfig dc;
    if (!o.airframe.empty()) dc.params = dynamics::airframe_by_name_or_path(o.airframe);
    dc.publish_rate_hz = o.dynamics_rate_hz;
    dc.mean_wind_W_mps = o.mean_wind_W_mps;
    dc.turbulence = dynamics::TurbulenceParams{o.turbulence, 10.0, 0.05};
    dc.seed = o.seed;
    const dynamics::QuadrotorModel model(dc.params);
    dc.initial_state.energy_used_J = (1.0 - o.initial_battery_pct / 100.0) * model.battery_energy_J();
    dynamics_ = std::make_unique<dynamics::DynamicsNode>(dc);

    bridge::BridgeNodeConfig bc;
    bc.seed = o.seed;
    bridge_ = std::make_unique<bridge::BridgeNode>(*bridge_port_, bc);

    bridge::FcNodeConfig fc;
    fc.params.vehicle = rigs::fc_vehicle_from_airframe(dc.params);
    fc.params.fence = o.fence;
    if (o.tune) o.tune(fc.params);
    fc_ = std::make_unique<bridge::FcNode>(*fc_port_, fc);

    rt_.add(ground);
    rt_.add(*dynamics_);
    rt_.add(*bridge_);
    rt_.add(*fc_);
  }

  void run_until(double t_s) { rt_.run_until(static_cast<int64_t>(std::llround(t_s * 1e6))); }
  double now_s() const { return rt_.clock().now_s(); }
  // Runs until pred() holds (checked at every state) or t_max_s; returns whether it held.
  bool run_until_true(const std::function<bool()>& pred, double t_max_s) {
    bool held = false;
    const auto previous = ground.on_state;
    ground.on_state = [&](const a3lcm::vehicle_state_t& s) {
      if (previous) previous(s);
      if (!held && pred()) {
        held = true;
        rt_.scheduler().request_stop();
      }
    };
    run_until(t_max_s);
    ground.on_state = previous;
    return held;
  }

  Eigen::Vector3d p_W_m() const { return {ground.state.p_W_m[0], ground.state.p_W_m[1], ground.state.p_W_m[2]}; }
  const dynamics::DynamicsNode& dynamics() const { return *dynamics_; }
  const bridge::BridgeNode& bridge() const { return *bridge_; }
  const bridge::FcNode& fc() const { return *fc_; }
  const bridge::VirtualCanBus& can() const { return can_; }

  GroundStation ground;

 private:
  common::VirtualRuntime rt_;
  bridge::VirtualCanBus can_;
  std::unique_ptr<bridge::CanBus> fc_port_, bridge_port_;
  std::unique_ptr<dynamics::DynamicsNode> dynamics_;
  std::unique_ptr<bridge::BridgeNode> bridge_;
  std::unique_ptr<bridge::FcNode> fc_;
};

}  // namespace a3::test
