// The integrators on the same model: ODE and RK4 agree with CVODE (the accuracy reference) on a
// 10 s open-loop manoeuvre, RK4 also after 60 s of the closed-loop patrol flight, and each
// reproduces the physics a hand calculation predicts (hover, free fall, yaw torque, energy drain).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "bench/dynamics/flight_controller.hpp"
#include "dynamics/integrator.hpp"
#include "dynamics/rk4_integrator.hpp"
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

double position_difference_m(const VehicleState& a, const VehicleState& b) { return (a.p_W_m - b.p_W_m).norm(); }
double attitude_difference_deg(const VehicleState& a, const VehicleState& b) {
  return attitude_difference_rad(a.q_WB, b.q_WB) * 180.0 / M_PI;
}

// The 10 s open-loop manoeuvre (manoeuvre.hpp) with CVODE, the accuracy reference, and another
// integrator: they agree to 1 cm and 0.5 deg.
void expect_manoeuvre_agrees_with_cvode(IntegratorKind kind) {
  const QuadrotorModel model(default_vehicle_params());
  const VehicleState start = hovering_at(model, 50.0);
  auto command = [&](double t, const VehicleState&) { return a3::test::manoeuvre_command(model, t); };
  IntegratorOptions options;
  options.ode_step_s = 0.0005;
  const Flight cvode = fly(IntegratorKind::kCvode, model, start, 10.0, command, options);
  const Flight other = fly(kind, model, start, 10.0, command, options);
  const VehicleState& a = cvode.states.back();
  const VehicleState& b = other.states.back();
  // The manoeuvre really moved and turned the vehicle...
  EXPECT_GT((a.p_W_m - start.p_W_m).norm(), 5.0);
  EXPECT_GT(attitude_difference_rad(a.q_WB, start.q_WB), 0.1);
  // ...and the two integrators agree: 1 cm, 0.5°.
  std::cout << "after 10 s: travelled " << (a.p_W_m - start.p_W_m).norm() << " m, turned "
            << attitude_difference_rad(a.q_WB, start.q_WB) * 180 / M_PI << " deg; CVODE vs " << to_string(kind)
            << ": " << position_difference_m(a, b) * 1000 << " mm, " << attitude_difference_deg(a, b) << " deg\n";
  EXPECT_LT(position_difference_m(a, b), 0.01) << "cvode " << a.p_W_m.transpose() << " " << to_string(kind) << " "
                                               << b.p_W_m.transpose();
  EXPECT_LT(attitude_difference_deg(a, b), 0.5);
  EXPECT_TRUE(cvode.events.empty());
  EXPECT_TRUE(other.events.empty());
}

TEST(IntegratorAgreement, CvodeAndOdeAgreeAfterTenSecondsOfFlight) {
  expect_manoeuvre_agrees_with_cvode(IntegratorKind::kOde);
}

TEST(IntegratorAgreement, CvodeAndRk4AgreeAfterTenSecondsOfFlight) {
  expect_manoeuvre_agrees_with_cvode(IntegratorKind::kRk4);
}

// The benchmarks' closed-loop patrol flight (bench/dynamics/flight_controller.hpp): take-off
// from the ground, legs, turns and climbs, a command that changes every 10 ms computed from the
// state, as the controller node does half a period after each step.
Flight fly_patrol(IntegratorKind kind, const QuadrotorModel& model, double duration_s, bool windy) {
  const Eigen::Vector3d mean_wind = windy ? wind_from_report(8.0, 240.0) : Eigen::Vector3d::Zero();
  WindField wind(mean_wind, TurbulenceParams{windy}, 42);
  auto integrator = make_integrator(kind, model, wind);
  integrator->reset(VehicleState{}, 0.0);
  bench::FlightController controller(model.params(), bench::patrol_plan(duration_s));
  Flight run;
  const int steps = static_cast<int>(std::lround(duration_s / kPeriod_s));
  for (int k = 0; k < steps; ++k) {
    const auto throttle =
        controller.throttle(k * kPeriod_s + 0.5 * kPeriod_s, bench::input_of(integrator->state(), integrator->on_ground()));
    RotorSpeeds command;
    for (int i = 0; i < 4; ++i) command[i] = model.throttle_to_speed_radps(throttle[i]);
    integrator->advance_to((k + 1) * kPeriod_s, command);
    run.states.push_back(integrator->state());
    for (auto& e : integrator->take_events()) run.events.push_back(e);
  }
  return run;
}

void expect_patrol_agrees_with_cvode(IntegratorKind kind, bool windy) {
  const QuadrotorModel model(default_vehicle_params());
  const Flight cvode = fly_patrol(IntegratorKind::kCvode, model, 60.0, windy);
  const Flight other = fly_patrol(kind, model, 60.0, windy);
  double travelled_m = 0.0, worst_m = 0.0, worst_deg = 0.0;
  for (std::size_t k = 0; k < cvode.states.size(); ++k) {
    if (k > 0) travelled_m += position_difference_m(cvode.states[k], cvode.states[k - 1]);
    worst_m = std::max(worst_m, position_difference_m(cvode.states[k], other.states[k]));
    worst_deg = std::max(worst_deg, attitude_difference_deg(cvode.states[k], other.states[k]));
  }
  const VehicleState& a = cvode.states.back();
  const VehicleState& b = other.states.back();
  std::cout << "patrol, 60 s" << (windy ? ", 8 m/s wind + turbulence" : ", calm") << ": travelled " << travelled_m
            << " m; CVODE vs " << to_string(kind) << " at 60 s: " << position_difference_m(a, b) * 1000 << " mm, "
            << attitude_difference_deg(a, b) << " deg (worst over the flight " << worst_m * 1000 << " mm, "
            << worst_deg << " deg)\n";
  EXPECT_GT(travelled_m, 150.0);  // took off, flew legs and turns
  EXPECT_GT(a.p_W_m.z(), 20.0);
  EXPECT_LT(position_difference_m(a, b), 0.01);
  EXPECT_LT(attitude_difference_deg(a, b), 0.5);
  // Thrust hovers around the weight on the ground before take-off (more so with vertical gusts):
  // contact events may come in a burst, but the burst ends at the same time, without a crash.
  for (const Flight* f : {&cvode, &other}) {
    ASSERT_FALSE(f->events.empty());
    EXPECT_EQ(f->events.front().kind, DynamicsEvent::Kind::kLiftoff);
    for (const auto& e : f->events) EXPECT_NE(e.kind, DynamicsEvent::Kind::kCrash);
  }
  EXPECT_NEAR(other.events.back().time_s, cvode.events.back().time_s, 0.02);
}

TEST(IntegratorAgreement, CvodeAndRk4AgreeAfterSixtySecondsOfThePatrolFlight) {
  expect_patrol_agrees_with_cvode(IntegratorKind::kRk4, false);
}

TEST(IntegratorAgreement, CvodeAndRk4AgreeAfterSixtySecondsOfThePatrolFlightInTurbulence) {
  expect_patrol_agrees_with_cvode(IntegratorKind::kRk4, true);
}

// The benchmark controller computes only the three entries of its attitude error it uses; they
// must be bit for bit those of the two full 3x3 products, or its commands (and every benchmark
// trajectory) would change.
TEST(FlightController, AttitudeErrorIsBitForBitTheFullProducts) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const auto random_rotation = [&] {
    return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized().toRotationMatrix();
  };
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Matrix3d R_des = random_rotation();
    const Eigen::Matrix3d R = random_rotation();
    const Eigen::Matrix3d E = 0.5 * (R_des.transpose() * R - R.transpose() * R_des);
    const Eigen::Vector3d e_R = bench::attitude_error(R_des, R);
    ASSERT_EQ(e_R.x(), E(2, 1)) << k;
    ASSERT_EQ(e_R.y(), E(0, 2)) << k;
    ASSERT_EQ(e_R.z(), E(1, 0)) << k;
  }
}

TEST(IntegratorAgreement, Rk4LandsExactlyOnTheRequestedTimes) {
  const QuadrotorModel model(default_vehicle_params());
  WindField wind(Eigen::Vector3d::Zero(), TurbulenceParams{false}, 1);
  Rk4Integrator rk4(model, wind, 0.0);
  EXPECT_DOUBLE_EQ(rk4.max_step_s(), 0.4 * 0.0125);  // the Iris' motor lag up
  rk4.reset(hovering_at(model, 10.0), 0.0);
  const RotorSpeeds hover{model.hover_speed_radps(), model.hover_speed_radps(), model.hover_speed_radps(),
                          model.hover_speed_radps()};
  // 4 ms (the rig's 250 Hz): one step; 10 ms: two of 5 ms; 3.3 ms then 7 ms: one, then two.
  rk4.advance_to(0.004, hover);
  EXPECT_EQ(rk4.time_s(), 0.004);
  EXPECT_EQ(rk4.stats().steps, 1);
  rk4.advance_to(0.014, hover);
  EXPECT_EQ(rk4.time_s(), 0.014);
  EXPECT_EQ(rk4.stats().steps, 3);
  for (int k = 1; k <= 1000; ++k) rk4.advance_to(0.014 + k * 0.0033, hover);
  EXPECT_EQ(rk4.time_s(), 0.014 + 1000 * 0.0033);
  EXPECT_EQ(rk4.stats().steps, 1003);
  EXPECT_EQ(rk4.stats().rhs_evaluations, 4 * 1003);
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

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, Integrators,
                         ::testing::Values(IntegratorKind::kRk4, IntegratorKind::kCvode, IntegratorKind::kOde),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace a3::dynamics
