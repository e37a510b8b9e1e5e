// The two integrators on the same model: they agree on a 10 s flight, and each reproduces the
// physics a hand calculation predicts (hover, free fall, yaw torque, energy drain).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "dynamics/integrator.hpp"
#include "tests/dynamics/manoeuvre.hpp"

namespace a3::dynamics {
namespace {

constexpr double kPeriod_s = 0.01;

VehicleState hovering_at(const QuadrotorModel& model, double z_m) {
  VehicleState s;
  s.p_W_m = {0, 0, z_m};
  s.rotor_speed_radps.fill(model.hover_speed_radps());
  return s;
}

struct Flight {
  std::vector<VehicleState> states;
  std::vector<DynamicsEvent> events;
};

template <typename CommandFn>
Flight fly(IntegratorKind kind, const QuadrotorModel& model, const VehicleState& start,
        double duration_s, CommandFn command, IntegratorOptions options = {},
        Eigen::Vector3d wind = Eigen::Vector3d::Zero()) {
  WindField field(wind, TurbulenceParams{false}, 1);
  auto integrator = make_integrator(kind, model, field, options);
  integrator->reset(start, 0.0);
  Flight run;
  const int steps = static_cast<int>(std::lround(duration_s / kPeriod_s));
  for (int k = 0; k < steps; ++k) {
    integrator->advance_to((k + 1) * kPeriod_s, command(k * kPeriod_s, integrator->state()));
    run.states.push_back(integrator->state());
    for (auto& e : integrator->take_events()) run.events.push_back(e);
  }
  return run;
}

class Integrators : public ::testing::TestWithParam<IntegratorKind> {
 protected:
  QuadrotorModel model_{default_vehicle_params()};
};

TEST(IntegratorAgreement, CvodeAndOdeAgreeAfterTenSecondsOfFlight) {
  const QuadrotorModel model(default_vehicle_params());
  const VehicleState start = hovering_at(model, 50.0);
  auto command = [&](double t, const VehicleState&) { return a3::test::manoeuvre_command(model, t); };
  IntegratorOptions options;
  options.ode_step_s = 0.0005;
  const Flight cvode = fly(IntegratorKind::kCvode, model, start, 10.0, command, options);
  const Flight ode = fly(IntegratorKind::kOde, model, start, 10.0, command, options);
  const VehicleState& a = cvode.states.back();
  const VehicleState& b = ode.states.back();
  // The manoeuvre really moved and turned the vehicle...
  EXPECT_GT((a.p_W_m - start.p_W_m).norm(), 5.0);
  EXPECT_GT(attitude_difference_rad(a.q_WB, start.q_WB), 0.1);
  // ...and the two integrators agree: 1 cm, 0.5°.
  std::cout << "after 10 s: travelled " << (a.p_W_m - start.p_W_m).norm() << " m, turned "
            << attitude_difference_rad(a.q_WB, start.q_WB) * 180 / M_PI << " deg; CVODE vs ODE: "
            << (a.p_W_m - b.p_W_m).norm() * 1000 << " mm, "
            << attitude_difference_rad(a.q_WB, b.q_WB) * 180 / M_PI << " deg\n";
  EXPECT_LT((a.p_W_m - b.p_W_m).norm(), 0.01) << "cvode " << a.p_W_m.transpose() << " ode " << b.p_W_m.transpose();
  EXPECT_LT(attitude_difference_rad(a.q_WB, b.q_WB) * 180.0 / M_PI, 0.5);
  EXPECT_TRUE(cvode.events.empty());
  EXPECT_TRUE(ode.events.empty());
}

TEST_P(Integrators, HoverCommandHoldsAltitude) {
  const VehicleState start = hovering_at(model_, 20.0);
  const double hover = model_.throttle_to_speed_radps(model_.hover_throttle());
  const Flight run = fly(GetParam(), model_, start, 10.0, [&](double, const VehicleState&) { return RotorSpeeds{hover, hover, hover, hover}; });
  const VehicleState& end = run.states.back();
  EXPECT_NEAR(end.p_W_m.z(), 20.0, 0.01);
  EXPECT_NEAR(end.p_W_m.x(), 0.0, 1e-6);
  EXPECT_NEAR(end.v_W_mps.norm(), 0.0, 1e-3);
  EXPECT_LT(attitude_difference_rad(end.q_WB, start.q_WB), 1e-6);
}

TEST_P(Integrators, FreeFallMatchesG) {
  VehicleParams p = default_vehicle_params();
  p.aero = AeroParams{};  // no drag: the fall is ½ g t²
  const QuadrotorModel model(p);
  VehicleState start;
  start.p_W_m = {0, 0, 100};
  const Flight run = fly(GetParam(), model, start, 3.0, [](double, const VehicleState&) { return RotorSpeeds{}; });
  const double t = 3.0;
  EXPECT_NEAR(run.states.back().p_W_m.z(), 100.0 - 0.5 * kGravity_mps2 * t * t, 0.01);
  EXPECT_NEAR(run.states.back().v_W_mps.z(), -kGravity_mps2 * t, 1e-3);
}

TEST_P(Integrators, PureYawTorqueSpinsAboutZOnly) {
  // Speed up the CW pair and slow the CCW pair so thrust stays equal to weight:
  // ω_cw² + ω_ccw² = 2 ω_h²; yaw torque = 2 k_m (ω_cw² - ω_ccw²), counter-clockwise.
  VehicleParams p = default_vehicle_params();
  p.aero.angular_drag_Nms_per_rad = 0.0;
  const QuadrotorModel model(p);
  const double wh2 = std::pow(model.hover_speed_radps(), 2);
  const double w_cw = std::sqrt(wh2 * 1.1), w_ccw = std::sqrt(wh2 * 0.9);
  VehicleState start = hovering_at(model, 30.0);
  start.rotor_speed_radps = {w_ccw, w_ccw, w_cw, w_cw};  // already spun up
  const Flight run = fly(GetParam(), model, start, 1.5, [&](double, const VehicleState&) { return RotorSpeeds{w_ccw, w_ccw, w_cw, w_cw}; });
  const double torque = 2.0 * p.rotor.drag_torque_coeff_Nm_per_radps2 * (w_cw * w_cw - w_ccw * w_ccw);
  const double expected_rate = torque / p.inertia_zz_kgm2 * 1.5;
  const VehicleState& end = run.states.back();
  EXPECT_NEAR(end.w_B_radps.z(), expected_rate, 1e-3 * expected_rate);
  EXPECT_GT(expected_rate, 0.5);
  EXPECT_NEAR(end.w_B_radps.x(), 0.0, 1e-9);
  EXPECT_NEAR(end.w_B_radps.y(), 0.0, 1e-9);
  EXPECT_NEAR(end.p_W_m.z(), 30.0, 1e-3);
  EXPECT_NEAR(roll_pitch_yaw_rad(end.q_WB).z(), 0.5 * torque / p.inertia_zz_kgm2 * 1.5 * 1.5, 2e-3);
}

TEST_P(Integrators, EnergyDrainMatchesAHandCalculation) {
  const VehicleParams p = with_payloads(default_vehicle_params(), {{"camera", 0.5, 0.01, 20.0}});
  const QuadrotorModel model(p);
  const VehicleState start = hovering_at(model, 40.0);
  const double hover = model.hover_speed_radps();
  const Flight run = fly(GetParam(), model, start, 60.0, [&](double, const VehicleState&) { return RotorSpeeds{hover, hover, hover, hover}; });
  // Per rotor T = m g / 4, induced power T^1.5 / (FM √(2 ρ π r²)); electrical = 4 P / η plus
  // avionics (5 W) and the payload (20 W).
  const double m = 1.5 + 0.5;
  const double T = m * 9.80665 / 4.0;
  const double area = M_PI * 0.127 * 0.127;
  const double rotor_W = std::pow(T, 1.5) / (0.6 * std::sqrt(2.0 * 1.225 * area));
  const double power_W = 4.0 * rotor_W / 0.8 + 5.0 + 20.0;
  EXPECT_NEAR(run.states.back().energy_used_J, power_W * 60.0, 1e-4 * power_W * 60.0);
  EXPECT_GT(power_W, 150.0);
  EXPECT_LT(power_W, 400.0);
}

TEST_P(Integrators, RestsOnTheGroundTakesOffAndLandsWithoutSinking) {
  VehicleState start;  // on the ground, rotors stopped
  const double hover = model_.hover_speed_radps();
  // Half thrust for a second (stays down), then a vertical-speed loop: climb at 2 m/s for 2 s,
  // then descend at 0.5 m/s until well after touchdown.
  auto command = [&](double t, const VehicleState& s) {
    double scale = 0.5;
    if (t >= 1.0) {
      const double vz_target = t < 3.0 ? 2.0 : -0.5;
      scale = std::sqrt(std::max(0.0, 1.0 + 0.5 * (vz_target - s.v_W_mps.z())));
    }
    return RotorSpeeds{hover * scale, hover * scale, hover * scale, hover * scale};
  };
  const Flight run = fly(GetParam(), model_, start, 20.0, command);
  EXPECT_NEAR(run.states[90].p_W_m.z(), 0.0, 2e-3);
  double peak = 0.0, lowest = 0.0;
  for (const auto& s : run.states) {
    peak = std::max(peak, s.p_W_m.z());
    lowest = std::min(lowest, s.p_W_m.z());
  }
  EXPECT_GT(peak, 2.0);
  EXPECT_GT(lowest, -0.005);  // never through the floor
  EXPECT_NEAR(run.states.back().p_W_m.z(), 0.0, 5e-3);
  int liftoffs = 0, touchdowns = 0, crashes = 0;
  for (const auto& e : run.events) {
    liftoffs += e.kind == DynamicsEvent::Kind::kLiftoff;
    touchdowns += e.kind == DynamicsEvent::Kind::kTouchdown;
    crashes += e.kind == DynamicsEvent::Kind::kCrash;
    if (e.kind == DynamicsEvent::Kind::kTouchdown) {
      EXPECT_GT(e.vertical_speed_mps, -1.0);
    }
  }
  EXPECT_GE(liftoffs, 1);
  EXPECT_GE(touchdowns, 1);
  EXPECT_EQ(crashes, 0);
}

// Touching down while the rotors still give more thrust than weight leaves the vehicle just
// above the floor; when the thrust then drops it must settle on the ground, not sink into it.
TEST_P(Integrators, ATouchdownUnderThrustNeverSinksThroughTheFloor) {
  const double hover = model_.hover_speed_radps();
  VehicleState start;
  start.p_W_m = {0, 0, 0.05};
  start.v_W_mps = {0, 0, -0.5};
  const double up = hover * std::sqrt(1.02), down = hover * std::sqrt(0.9);
  start.rotor_speed_radps = {up, up, up, up};
  const Flight run = fly(GetParam(), model_, start, 4.0, [&](double t, const VehicleState&) {
    const double w = t < 0.5 ? up : down;
    return RotorSpeeds{w, w, w, w};
  });
  double lowest = 0.0;
  for (const auto& s : run.states) lowest = std::min(lowest, s.p_W_m.z());
  EXPECT_GT(lowest, -0.005);
  EXPECT_NEAR(run.states.back().p_W_m.z(), 0.0, 0.005);
  EXPECT_NEAR(run.states.back().v_W_mps.z(), 0.0, 0.05);
}

// Thrust that rises above weight while the rotors spin up, dips back below it and rises
// again: the vehicle lifts off each time the thrust exceeds the weight, whatever the history.
TEST_P(Integrators, LiftsOffWheneverThrustExceedsWeight) {
  const double hover = model_.hover_speed_radps();
  VehicleState start;
  const Flight run = fly(GetParam(), model_, start, 6.0, [&](double t, const VehicleState&) {
    const double scale = t < 1.0 ? 1.001 : t < 1.01 ? 0.98 : 1.1;
    return RotorSpeeds{hover * scale, hover * scale, hover * scale, hover * scale};
  });
  EXPECT_GT(run.states.back().p_W_m.z(), 2.0);
}

TEST_P(Integrators, AHardImpactIsACrashAndStopsTheMotors) {
  VehicleState start;
  start.p_W_m = {0, 0, 10};  // free fall from 10 m: 14 m/s at impact
  const Flight run = fly(GetParam(), model_, start, 3.0, [](double, const VehicleState&) { return RotorSpeeds{}; });
  ASSERT_FALSE(run.events.empty());
  EXPECT_EQ(run.events.front().kind, DynamicsEvent::Kind::kCrash);
  EXPECT_LT(run.events.front().vertical_speed_mps, -10.0);
  EXPECT_NEAR(run.states.back().p_W_m.z(), 0.0, 5e-3);
  EXPECT_NEAR(run.states.back().v_W_mps.norm(), 0.0, 0.05);
}

TEST_P(Integrators, NoThrustFromAnEmptyBattery) {
  VehicleState start = hovering_at(model_, 100.0);
  start.energy_used_J = model_.battery_energy_J() - 200.0;  // about one second of hover left
  const double hover = model_.hover_speed_radps();
  const Flight run = fly(GetParam(), model_, start, 3.0, [&](double, const VehicleState&) { return RotorSpeeds{hover, hover, hover, hover}; });
  bool empty = false;
  for (const auto& e : run.events) empty |= e.kind == DynamicsEvent::Kind::kBatteryEmpty;
  EXPECT_TRUE(empty);
  EXPECT_LT(run.states.back().rotor_speed_radps[0], 0.1 * hover);
  EXPECT_LT(run.states.back().p_W_m.z(), 98.0);  // falling
}

INSTANTIATE_TEST_SUITE_P(BothIntegrators, Integrators,
                         ::testing::Values(IntegratorKind::kCvode, IntegratorKind::kOde),
                         [](const auto& info) { return info.param == IntegratorKind::kCvode ? "cvode" : "ode"; });

}  // namespace
}  // namespace a3::dynamics
