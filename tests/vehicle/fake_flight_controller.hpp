// A small fake flight controller for the tool server's tests: answers fc_command_t with
// fc_status_t at once (accepting or refusing by simple rules), moves its reported position
// straight toward its target at its speed, publishes its status at 10 Hz and a "true"
// vehicle_state_t (its position plus a fixed offset, so tests can tell the two apart) at 20 Hz.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/channels.hpp"
#include "common/node.hpp"

namespace a3::vehicle::test {

struct FakeFcConfig {
  Eigen::Vector3d start_W_m = Eigen::Vector3d(20.0, 20.0, 0.0);
  Eigen::Vector3d true_offset_W_m = Eigen::Vector3d(0.25, -0.5, 0.0);  // true = estimate + this
  double battery_pct = 90.0;
  double max_altitude_m = 1000.0;  // GOTO above is refused
  double default_speed_mps = 5.0;
  double climb_mps = 2.0;
  double descent_mps = 1.0;
  double return_altitude_m = 30.0;
  bool answer_commands = true;  // false: never publishes a status (a dead fc)
};

class FakeFlightController final : public common::Node {
 public:
  explicit FakeFlightController(FakeFcConfig config = {}) : c_(config), p_(config.start_W_m), home_(config.start_W_m) {
    home_.z() = 0.0;
    speed_ = c_.default_speed_mps;
    battery_ = c_.battery_pct;
  }
  std::string name() const override { return "fake_fc"; }

  void start(common::Executor& executor, common::Bus& bus) override {
    executor_ = &executor;
    bus_ = &bus;
    bus.subscribe<a3lcm::fc_command_t>(common::channels::kFcCommand.of(0),
                                       [this](const a3lcm::fc_command_t& c, int64_t) { on_command(c); });
    executor.schedule_every(50'000, [this] { tick(0.05); });
    executor.schedule_every(100'000, [this] {
      if (c_.answer_commands) publish_status();
    });
  }

  // Test hooks.
  void set_battery(double pct) { battery_ = pct; }
  // A failsafe the fc decides on its own (e.g. link loss: hold; low battery: return home).
  void force_mode(int8_t mode, int8_t failsafe) {
    mode_ = mode;
    failsafe_ = failsafe;
    if (mode == a3lcm::fc_status_t::HOLD) target_ = p_;
    if (mode == a3lcm::fc_status_t::RETURN_HOME) return_phase_ = 0;
    publish_status();
  }
  const Eigen::Vector3d& position() const { return p_; }
  int8_t mode() const { return mode_; }
  double speed() const { return speed_; }

  std::vector<a3lcm::fc_command_t> commands;  // all but heartbeats
  int heartbeats = 0;

 private:
  void on_command(const a3lcm::fc_command_t& c) {
    if (c.command == a3lcm::fc_command_t::HEARTBEAT) {
      ++heartbeats;
      return;
    }
    commands.push_back(c);
    seq_ = c.seq;
    accepted_ = true;
    reason_.clear();
    const Eigen::Vector3d t(c.target_W_m[0], c.target_W_m[1], c.target_W_m[2]);
    switch (c.command) {
      case a3lcm::fc_command_t::TAKEOFF:
        if (battery_ < 20.0) {
          refuse("battery too low");
        } else {
          armed_ = true;
          mode_ = a3lcm::fc_status_t::TAKEOFF;
          target_ = Eigen::Vector3d(p_.x(), p_.y(), t.z());
        }
        break;
      case a3lcm::fc_command_t::GOTO:
        if (!armed_) {
          refuse("not armed");
        } else if (t.z() > c_.max_altitude_m) {
          refuse("above the altitude limit");
        } else {
          if (c.speed_limit_mps > 0.0) speed_ = std::min(c.speed_limit_mps, 12.0);
          if (std::isfinite(c.yaw_deg)) yaw_deg_ = c.yaw_deg;
          mode_ = a3lcm::fc_status_t::GOTO;
          target_ = t;
        }
        break;
      case a3lcm::fc_command_t::HOLD:
        if (!armed_) {
          refuse("not armed");
        } else {
          mode_ = a3lcm::fc_status_t::HOLD;
          target_ = p_;
        }
        break;
      case a3lcm::fc_command_t::LAND:
        if (!armed_) {
          refuse("not armed");
        } else {
          mode_ = a3lcm::fc_status_t::LAND;
        }
        break;
      case a3lcm::fc_command_t::RETURN_HOME:
        if (!armed_) {
          refuse("not armed");
        } else {
          mode_ = a3lcm::fc_status_t::RETURN_HOME;
          return_phase_ = 0;
        }
        break;
      case a3lcm::fc_command_t::SET_SPEED:
        if (!(c.speed_limit_mps > 0.0)) {
          refuse("speed must be > 0 m/s");
        } else {
          speed_ = std::min(c.speed_limit_mps, 12.0);
        }
        break;
      default:
        refuse("unknown command");
    }
    if (c_.answer_commands) publish_status();
  }

  void refuse(const std::string& why) {
    accepted_ = false;
    reason_ = why;
  }

  // Moves toward `goal` at `speed`; true on arrival.
  bool move_toward(const Eigen::Vector3d& goal, double speed, double dt) {
    const Eigen::Vector3d d = goal - p_;
    const double step = speed * dt;
    if (d.norm() <= step) {
      v_ = d / dt;
      p_ = goal;
      return true;
    }
    v_ = d.normalized() * speed;
    p_ += v_ * dt;
    return false;
  }

  void tick(double dt) {
    v_ = Eigen::Vector3d::Zero();
    switch (mode_) {
      case a3lcm::fc_status_t::TAKEOFF:
        if (move_toward(target_, c_.climb_mps, dt)) mode_ = a3lcm::fc_status_t::HOLD;
        break;
      case a3lcm::fc_status_t::GOTO:
        if (move_toward(target_, speed_, dt)) mode_ = a3lcm::fc_status_t::HOLD;
        break;
      case a3lcm::fc_status_t::LAND:
        if (move_toward(Eigen::Vector3d(p_.x(), p_.y(), 0.0), c_.descent_mps, dt)) {
          mode_ = a3lcm::fc_status_t::DISARMED;
          armed_ = false;
        }
        break;
      case a3lcm::fc_status_t::RETURN_HOME: {
        const double cruise = std::max(p_.z(), c_.return_altitude_m);
        if (return_phase_ == 0 && move_toward(Eigen::Vector3d(p_.x(), p_.y(), cruise), c_.climb_mps, dt)) {
          return_phase_ = 1;
        } else if (return_phase_ == 1 && move_toward(Eigen::Vector3d(home_.x(), home_.y(), p_.z()), speed_, dt)) {
          mode_ = a3lcm::fc_status_t::LAND;
        }
        break;
      }
      default:
        break;
    }
    a3lcm::vehicle_state_t s{};
    s.utime_us = executor_->clock().now_us();
    const Eigen::Vector3d truth = p_ + c_.true_offset_W_m;
    for (int k = 0; k < 3; ++k) {
      s.p_W_m[k] = truth[k];
      s.v_W_mps[k] = v_[k];
    }
    s.q_WB[0] = std::cos(yaw_deg_ * M_PI / 360.0);
    s.q_WB[3] = std::sin(yaw_deg_ * M_PI / 360.0);
    s.battery_pct = battery_;
    s.on_ground = !armed_ && p_.z() <= 0.05;
    bus_->publish(common::channels::kState.of(0), s);
  }

  void publish_status() {
    a3lcm::fc_status_t s{};
    s.utime_us = executor_->clock().now_us();
    s.mode = mode_;
    s.armed = armed_;
    s.failsafe = failsafe_;
    for (int k = 0; k < 3; ++k) {
      s.p_W_m[k] = p_[k];
      s.v_W_mps[k] = v_[k];
    }
    s.yaw_deg = yaw_deg_;
    s.battery_pct = battery_;
    s.last_command_seq = seq_;
    s.last_command_accepted = accepted_;
    s.last_command_reason = reason_;
    bus_->publish(common::channels::kFcStatus.of(0), s);
  }

  FakeFcConfig c_;
  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  Eigen::Vector3d p_, v_ = Eigen::Vector3d::Zero(), target_ = Eigen::Vector3d::Zero(), home_;
  double speed_ = 5.0, battery_ = 90.0, yaw_deg_ = 90.0;
  int8_t mode_ = a3lcm::fc_status_t::DISARMED;
  int8_t failsafe_ = a3lcm::fc_status_t::FAILSAFE_NONE;
  bool armed_ = false;
  int return_phase_ = 0;
  int32_t seq_ = -1;
  bool accepted_ = false;
  std::string reason_;
};

}  // namespace a3::vehicle::test
