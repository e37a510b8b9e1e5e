// A small closed-loop flight for the dynamics benchmarks and the trajectory plot: a waypoint
// plan (minimum-jerk segments between timed waypoints), a position controller (PID on position,
// acceleration feed-forward) over a geometric attitude controller (Lee et al., "Geometric
// tracking control of a quadrotor UAV on SE(3)", CDC 2010), and an exact mixer onto the four
// rotors from the airframe's own constants. It stands in for the autopilot a real episode has;
// its commands change every step, as an autopilot's do. Header-only, benchmark code.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "a3lcm/actuator_cmd_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/channels.hpp"
#include "common/node.hpp"
#include "dynamics/quadrotor_model.hpp"

namespace a3::bench {

struct Waypoint {
  double t_s;
  Eigen::Vector3d p_W_m;
  double yaw_deg;       // ENU: from east, counter-clockwise
  bool linear = false;  // reach it at constant speed (else minimum jerk)
};

struct Reference {
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_W_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_W_mps2 = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
  bool motors_off = false;  // before take-off and after the last waypoint once on the ground
};

class FlightPlan {
 public:
  // takeoff_s: motors start; the waypoints follow, in time order.
  FlightPlan(double takeoff_s, std::vector<Waypoint> waypoints)
      : takeoff_s_(takeoff_s), wp_(std::move(waypoints)) {
    if (wp_.empty()) throw std::invalid_argument("flight plan: no waypoints");
    for (std::size_t i = 1; i < wp_.size(); ++i) {
      if (!(wp_[i].t_s > wp_[i - 1].t_s)) throw std::invalid_argument("flight plan: waypoint times must increase");
    }
  }
  double end_s() const { return wp_.back().t_s; }
  double takeoff_s() const { return takeoff_s_; }

  Reference at(double t_s) const {
    Reference r;
    r.motors_off = t_s < takeoff_s_;
    if (t_s <= wp_.front().t_s) {
      r.p_W_m = wp_.front().p_W_m;
      r.yaw_rad = wp_.front().yaw_deg * M_PI / 180.0;
      return r;
    }
    if (t_s >= wp_.back().t_s) {
      r.p_W_m = wp_.back().p_W_m;
      r.yaw_rad = wp_.back().yaw_deg * M_PI / 180.0;
      return r;
    }
    const auto next = std::upper_bound(wp_.begin(), wp_.end(), t_s, [](double t, const Waypoint& w) { return t < w.t_s; });
    const Waypoint& b = *next;
    const Waypoint& a = *(next - 1);
    const double T = b.t_s - a.t_s;
    const double x = (t_s - a.t_s) / T;
    double s = x, ds = 1.0 / T, dds = 0.0;
    if (!b.linear) {  // minimum jerk: s = 10x³ - 15x⁴ + 6x⁵
      s = x * x * x * (10 - 15 * x + 6 * x * x);
      ds = 30 * x * x * (1 - x) * (1 - x) / T;
      dds = 60 * x * (1 - x) * (1 - 2 * x) / (T * T);
    }
    const Eigen::Vector3d d = b.p_W_m - a.p_W_m;
    r.p_W_m = a.p_W_m + s * d;
    r.v_W_mps = ds * d;
    r.a_W_mps2 = dds * d;
    r.yaw_rad = (a.yaw_deg + s * (b.yaw_deg - a.yaw_deg)) * M_PI / 180.0;
    return r;
  }

 private:
  double takeoff_s_;
  std::vector<Waypoint> wp_;
};

// Take-off, then a 40 s patrol repeated until end_s (legs east and north with turns and
// altitude changes, a diagonal back home), never landing: the speed benchmarks' flight.
inline FlightPlan patrol_plan(double end_s) {
  std::vector<Waypoint> w = {{1.0, {0, 0, 0}, 0}, {10.0, {0, 0, 30}, 0}};
  double yaw = 0.0;  // keeps growing: a turn is always to the left
  for (double t = 10.0; t < end_s + 40.0; t += 40.0, yaw += 360.0) {
    w.push_back({t + 8, {40, 0, 35}, yaw});
    w.push_back({t + 12, {40, 0, 35}, yaw + 90});
    w.push_back({t + 20, {40, 30, 25}, yaw + 90});
    w.push_back({t + 24, {40, 30, 25}, yaw + 225});
    w.push_back({t + 34, {0, 0, 30}, yaw + 225});
    w.push_back({t + 40, {0, 0, 30}, yaw + 360});
  }
  return FlightPlan(0.5, std::move(w));
}

// Take-off, climb, a loop of legs with a yaw turn, descent and a gentle landing: the plotted
// flight (about 75 s).
inline FlightPlan demo_plan() {
  return FlightPlan(1.0, {{2.0, {0, 0, 0}, 0},
                          {9.0, {0, 0, 20}, 0},         // climb to 20 m
                          {19.0, {40, 0, 20}, 0},       // 40 m east
                          {23.0, {40, 0, 20}, 90},      // turn to face north
                          {33.0, {40, 30, 30}, 90},     // 30 m north, climbing to 30 m
                          {37.0, {40, 30, 30}, 225},    // face home
                          {50.0, {0, 0, 25}, 225},      // fly home
                          {53.0, {0, 0, 25}, 360},      // face east again
                          {63.0, {0, 0, 2}, 360},       // descend
                          {68.0, {0, 0, -0.5}, 360, true}});  // touch down at 0.5 m/s
}

struct ControllerInput {
  Eigen::Vector3d p_W_m, v_W_mps, w_B_radps;
  Eigen::Quaterniond q_WB;
  bool on_ground = false;
};

inline ControllerInput input_of(const a3lcm::vehicle_state_t& s) {
  ControllerInput in;
  in.p_W_m = {s.p_W_m[0], s.p_W_m[1], s.p_W_m[2]};
  in.v_W_mps = {s.v_W_mps[0], s.v_W_mps[1], s.v_W_mps[2]};
  in.w_B_radps = {s.w_B_radps[0], s.w_B_radps[1], s.w_B_radps[2]};
  in.q_WB = Eigen::Quaterniond(s.q_WB[0], s.q_WB[1], s.q_WB[2], s.q_WB[3]);
  in.on_ground = s.on_ground;
  return in;
}

inline ControllerInput input_of(const dynamics::VehicleState& s, bool on_ground) {
  return {s.p_W_m, s.v_W_mps, s.w_B_radps, s.q_WB, on_ground};
}

// Entry (i, j) of ½ (Aᵀ B − Bᵀ A), each product's entry summed in Eigen's order (k = 0, 1, 2).
inline double skew_product_entry(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B, int i, int j) {
  const double atb = A(0, i) * B(0, j) + A(1, i) * B(1, j) + A(2, i) * B(2, j);
  const double bta = B(0, i) * A(0, j) + B(1, i) * A(1, j) + B(2, i) * A(2, j);
  return 0.5 * (atb - bta);
}

// Lee's attitude error e_R = vee(½ (R_desᵀ R − Rᵀ R_des)) from the three entries it uses, without
// the two full 3x3 products: bit for bit their result (tests/dynamics/test_integrators.cpp).
inline Eigen::Vector3d attitude_error(const Eigen::Matrix3d& R_des, const Eigen::Matrix3d& R) {
  return {skew_product_entry(R_des, R, 2, 1), skew_product_entry(R_des, R, 0, 2), skew_product_entry(R_des, R, 1, 0)};
}

class FlightController {
 public:
  FlightController(const dynamics::VehicleParams& params, FlightPlan plan, double period_s = 0.01)
      : model_(params), plan_(std::move(plan)), period_s_(period_s) {
    const double a = params.arm_length_m / std::sqrt(2.0);
    const double c = params.rotor.drag_torque_coeff_Nm_per_radps2 / params.rotor.thrust_coeff_N_per_radps2;
    Eigen::Matrix4d m;  // [T, τx, τy, τz] = m · [f0..f3]; rotor positions and spins as in the model
    m << 1, 1, 1, 1,  //
        -a, a, a, -a,  //
        -a, a, -a, a,  //
        -c, -c, c, c;
    mixer_inverse_ = m.inverse();
    inertia_ = {params.inertia_xx_kgm2, params.inertia_yy_kgm2, params.inertia_zz_kgm2};
  }

  const FlightPlan& plan() const { return plan_; }

  // Normalised throttles (0..1) at time t_s.
  std::array<double, 4> throttle(double t_s, const ControllerInput& s) {
    const Reference ref = plan_.at(t_s);
    const bool landed = t_s > plan_.end_s() - 3.0 && s.on_ground;
    if (ref.motors_off || landed) {
      integral_.setZero();
      return {0, 0, 0, 0};
    }
    const double m = model_.mass_kg();
    const double g = dynamics::kGravity_mps2;
    // Position loop: PID with acceleration feed-forward, the integral only once airborne.
    const Eigen::Vector3d e_p = ref.p_W_m - s.p_W_m;
    if (!s.on_ground) integral_ = (integral_ + e_p * period_s_).cwiseMax(-kIntegralLimit).cwiseMin(kIntegralLimit);
    Eigen::Vector3d a_cmd = kKp.cwiseProduct(e_p) + kKd.cwiseProduct(ref.v_W_mps - s.v_W_mps) +
                            kKi.cwiseProduct(integral_) + ref.a_W_mps2;
    const double horizontal = a_cmd.head<2>().norm();
    if (horizontal > kMaxTilt_mps2) a_cmd.head<2>() *= kMaxTilt_mps2 / horizontal;
    a_cmd.z() = std::clamp(a_cmd.z(), -0.6 * g, 0.8 * g);
    const Eigen::Vector3d force_W = m * (a_cmd + Eigen::Vector3d(0, 0, g));
    // Attitude: body z along the force, body x toward the heading.
    const Eigen::Matrix3d R = s.q_WB.normalized().toRotationMatrix();
    const Eigen::Vector3d b3 = force_W.normalized();
    const Eigen::Vector3d heading(std::cos(ref.yaw_rad), std::sin(ref.yaw_rad), 0.0);
    const Eigen::Vector3d b2 = b3.cross(heading).normalized();
    Eigen::Matrix3d R_des;
    R_des.col(0) = b2.cross(b3);
    R_des.col(1) = b2;
    R_des.col(2) = b3;
    const double thrust_N = std::max(0.0, force_W.dot(R.col(2)));
    const Eigen::Vector3d e_R = attitude_error(R_des, R);
    const Eigen::Vector3d& w = s.w_B_radps;
    const Eigen::Vector3d torque = -kKr.cwiseProduct(inertia_).cwiseProduct(e_R) -
                                   kKw.cwiseProduct(inertia_).cwiseProduct(w) +
                                   w.cross(inertia_.cwiseProduct(w));
    const Eigen::Vector4d f = mixer_inverse_ * Eigen::Vector4d(thrust_N, torque.x(), torque.y(), torque.z());
    const auto& rotor = model_.params().rotor;
    std::array<double, 4> out;
    for (int i = 0; i < 4; ++i) {
      const double speed = std::sqrt(std::max(0.0, f[i]) / rotor.thrust_coeff_N_per_radps2);
      out[i] = std::clamp(speed / rotor.max_speed_radps, 0.05, 1.0);  // idle: props keep turning
    }
    return out;
  }

 private:
  inline static const Eigen::Vector3d kKp{2.0, 2.0, 4.0};   // 1/s²
  inline static const Eigen::Vector3d kKd{2.6, 2.6, 3.5};   // 1/s
  inline static const Eigen::Vector3d kKi{0.4, 0.4, 0.8};   // 1/s³
  inline static const Eigen::Vector3d kKr{150, 150, 30};    // attitude, 1/s² (times inertia)
  inline static const Eigen::Vector3d kKw{20, 20, 9};       // rate, 1/s (times inertia)
  static constexpr double kIntegralLimit = 2.0;             // m·s
  static constexpr double kMaxTilt_mps2 = 6.0;              // horizontal acceleration limit

  dynamics::QuadrotorModel model_;
  FlightPlan plan_;
  double period_s_;
  Eigen::Matrix4d mixer_inverse_;
  Eigen::Vector3d inertia_;
  Eigen::Vector3d integral_ = Eigen::Vector3d::Zero();
};

// The controller as a node: listens to A3_STATE, publishes A3_ACTUATORS on a 100 Hz grid
// offset by half a period from the dynamics steps (as ActuatorScriptNode does).
class FlightControllerNode final : public common::Node {
 public:
  FlightControllerNode(const dynamics::VehicleParams& params, FlightPlan plan, double rate_hz = 100.0,
                       double offset_s = 0.005)
      : controller_(params, std::move(plan), 1.0 / rate_hz),
        period_us_(static_cast<int64_t>(std::llround(1e6 / rate_hz))),
        offset_us_(static_cast<int64_t>(std::llround(offset_s * 1e6))) {}
  std::string name() const override { return "flight_controller"; }
  void start(common::Executor& executor, common::Bus& bus) override {
    bus_ = &bus;
    bus.subscribe<a3lcm::vehicle_state_t>(common::channels::kState.of(0), [this](const a3lcm::vehicle_state_t& s, int64_t) {
      state_ = s;
      have_state_ = true;
      ++states_received_;
    });
    const int64_t now_us = executor.clock().now_us();
    next_us_ = (now_us - offset_us_ + period_us_ - 1) / period_us_ * period_us_ + offset_us_;
    executor.schedule(next_us_, period_us_, [this] { tick(); });
  }
  uint64_t published() const { return published_; }
  // The states heard on the bus: how many, and the last (zero before the first).
  uint64_t states_received() const { return states_received_; }
  const a3lcm::vehicle_state_t& last_state() const { return state_; }

 private:
  void tick() {
    const int64_t t_us = next_us_;  // the grid time, not the (possibly late) clock
    next_us_ += period_us_;
    if (!have_state_) return;
    a3lcm::actuator_cmd_t cmd;
    cmd.utime_us = t_us;
    const auto throttle = controller_.throttle(t_us * 1e-6, input_of(state_));
    for (int i = 0; i < 4; ++i) cmd.throttle[i] = throttle[i];
    cmd.armed = true;
    bus_->publish(common::channels::kActuators.of(0), cmd);
    ++published_;
  }

  FlightController controller_;
  common::Bus* bus_ = nullptr;
  int64_t period_us_, offset_us_, next_us_ = 0;
  a3lcm::vehicle_state_t state_{};
  bool have_state_ = false;
  uint64_t states_received_ = 0;
  uint64_t published_ = 0;
};

}  // namespace a3::bench
