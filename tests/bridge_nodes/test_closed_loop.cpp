// The checks on the full loop in virtual time: dynamics node + bridge node + fc node,
// LCM between dynamics, bridge and ground, DroneCAN on a virtual CAN bus between bridge and fc.
// Take-off and hold (still air, 8 m/s wind with turbulence), a 50 m go-to, landing, each
// failsafe when its condition is created (and not otherwise), refusal of a target outside the
// geofence with its reason on A3_FC_STATUS.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "dynamics/wind_field.hpp"
#include "tests/bridge_nodes/closed_loop.hpp"

namespace a3::bridge {
namespace {

using a3::test::ClosedLoop;
using a3::test::LoopOptions;
using Cmd = a3lcm::fc_command_t;
using Status = a3lcm::fc_status_t;
// Values, not references to lcm-gen's static members (which have no definition).
constexpr int8_t kDisarmed = a3lcm::fc_status_t::DISARMED;
constexpr int8_t kFailsafeGeofence = a3lcm::fc_status_t::FAILSAFE_GEOFENCE;
constexpr int8_t kFailsafeLinkLoss = a3lcm::fc_status_t::FAILSAFE_LINK_LOSS;
constexpr int8_t kFailsafeLowBattery = a3lcm::fc_status_t::FAILSAFE_LOW_BATTERY;
constexpr int8_t kFailsafeNone = a3lcm::fc_status_t::FAILSAFE_NONE;
constexpr int8_t kHold = a3lcm::fc_status_t::HOLD;
constexpr int8_t kLand = a3lcm::fc_status_t::LAND;
constexpr int8_t kReturnHome = a3lcm::fc_status_t::RETURN_HOME;

// Waits for the estimator (sensor frames) and takes off to altitude_m; asserts it got there.
void take_off(ClosedLoop& loop, double altitude_m) {
  loop.run_until(loop.now_s() + 1.0);
  const int32_t seq = loop.ground.command(Cmd::TAKEOFF, 0, 0, altitude_m);
  loop.run_until(loop.now_s() + 0.1);
  const Status* s = loop.ground.status_for(seq);
  ASSERT_NE(s, nullptr) << "no A3_FC_STATUS for the take-off command";
  ASSERT_TRUE(s->last_command_accepted) << s->last_command_reason;
  ASSERT_TRUE(loop.run_until_true([&] { return loop.ground.last_status().mode == kHold; }, loop.now_s() + 20.0))
      << "take-off did not end in hold; z = " << loop.p_W_m().z();
}

// RMS of (true z - target) over [now, now + duration_s].
double altitude_rms_m(ClosedLoop& loop, double target_m, double duration_s) {
  double sum = 0.0;
  int n = 0;
  loop.ground.on_state = [&](const a3lcm::vehicle_state_t& s) {
    sum += (s.p_W_m[2] - target_m) * (s.p_W_m[2] - target_m);
    ++n;
  };
  loop.run_until(loop.now_s() + duration_s);
  loop.ground.on_state = nullptr;
  return std::sqrt(sum / std::max(n, 1));
}

TEST(ClosedLoop, TakesOffToTenMetresAndHoldsInStillAir) {
  ClosedLoop loop;
  take_off(loop, 10.0);
  loop.run_until(15.0);
  const double rms = altitude_rms_m(loop, 10.0, 20.0);
  std::cout << "full loop, hold at 10 m, still air: altitude RMS error " << rms << " m\n";
  EXPECT_LE(rms, 0.1);
  EXPECT_LT(loop.p_W_m().head<2>().norm(), 0.5);
  EXPECT_EQ(loop.ground.last_status().mode, kHold);
  EXPECT_EQ(loop.ground.max_failsafe_seen, kFailsafeNone);  // heartbeats flowed, battery full
  // The sensors reached the fc at their rates (35 s: IMU 200 Hz, GNSS 10 Hz, baro 50 Hz).
  const auto& c = loop.fc().counters();
  EXPECT_NEAR(c.get("imu") / 35.0, 200.0, 2.0);
  EXPECT_NEAR(c.get("gnss") / 35.0, 10.0, 0.2);
  EXPECT_NEAR(c.get("baro") / 35.0, 50.0, 0.5);
  EXPECT_EQ(c.get("sensor_rejected"), 0u);
  EXPECT_NEAR(loop.bridge().counters().get("esc_frames") / 35.0, 250.0, 2.0);
  std::cout << "CAN bus load " << loop.can().stats().load(35'000'000) * 100 << " %\n";
}

TEST(ClosedLoop, FliesTheHeavyLiftAirframeWhenToldIt) {
  LoopOptions o;
  o.airframe = "heavy-lift";  // the fc's vehicle section comes from the same airframe
  ClosedLoop loop(o);
  take_off(loop, 10.0);
  loop.run_until(20.0);
  const double rms = altitude_rms_m(loop, 10.0, 10.0);
  std::cout << "full loop, heavy-lift airframe, hold at 10 m: altitude RMS error " << rms << " m\n";
  EXPECT_LE(rms, 0.1);
  EXPECT_LT(loop.p_W_m().head<2>().norm(), 0.5);
}

TEST(ClosedLoop, HoldsInEightMetrePerSecondWindWithTurbulence) {
  LoopOptions o;
  o.mean_wind_W_mps = dynamics::wind_from_report(8.0, 240.0);
  o.turbulence = true;
  o.seed = 3;
  ClosedLoop loop(o);
  take_off(loop, 10.0);
  loop.run_until(20.0);
  const double rms = altitude_rms_m(loop, 10.0, 30.0);
  std::cout << "full loop, hold at 10 m, 8 m/s wind with turbulence: altitude RMS error " << rms << " m, "
            << "horizontal offset " << loop.p_W_m().head<2>().norm() << " m\n";
  EXPECT_LE(rms, 0.5);
  EXPECT_LT(loop.p_W_m().head<2>().norm(), 3.0);
  EXPECT_EQ(loop.ground.max_failsafe_seen, kFailsafeNone);
}

TEST(ClosedLoop, FiftyMetreGoToSettlesWithinFivePercentWithoutOvershoot) {
  ClosedLoop loop;
  take_off(loop, 10.0);
  loop.run_until(12.0);
  const double t0 = loop.now_s();
  const int32_t seq = loop.ground.command(Cmd::GOTO, 50.0, 0.0, 10.0, 6.0);
  double max_x = 0.0, settled_at = -1.0;
  loop.ground.on_state = [&](const a3lcm::vehicle_state_t& s) {
    max_x = std::max(max_x, s.p_W_m[0]);
    const bool inside = std::abs(s.p_W_m[0] - 50.0) <= 0.05 * 50.0;
    if (inside && settled_at < 0) settled_at = s.utime_us * 1e-6;
    if (!inside) settled_at = -1.0;
  };
  loop.run_until(t0 + 28.0);
  loop.ground.on_state = nullptr;
  const Status* s = loop.ground.status_for(seq);
  ASSERT_NE(s, nullptr);
  EXPECT_TRUE(s->last_command_accepted) << s->last_command_reason;
  const double overshoot = (max_x - 50.0) / 50.0;
  std::cout << "full loop, 50 m go-to at 6 m/s: overshoot " << overshoot * 100 << " %, settled within 5 % after "
            << settled_at - t0 << " s, final error " << std::abs(loop.p_W_m().x() - 50.0) << " m\n";
  EXPECT_LE(overshoot, 0.10);
  EXPECT_GT(settled_at, 0.0);  // inside the band and stayed there
  EXPECT_NEAR(loop.p_W_m().x(), 50.0, 0.05 * 50.0);
  EXPECT_NEAR(loop.p_W_m().z(), 10.0, 0.5);
  EXPECT_EQ(loop.ground.last_status().mode, kHold);  // arrived
}

TEST(ClosedLoop, LandEndsDisarmedOnTheGround) {
  ClosedLoop loop;
  take_off(loop, 8.0);
  loop.run_until(10.0);
  const int32_t seq = loop.ground.command(Cmd::LAND);
  loop.run_until(30.0);
  ASSERT_NE(loop.ground.status_for(seq), nullptr);
  EXPECT_TRUE(loop.ground.status_for(seq)->last_command_accepted);
  EXPECT_EQ(loop.ground.last_status().mode, kDisarmed);
  EXPECT_FALSE(loop.ground.last_status().armed);
  EXPECT_TRUE(loop.ground.state.on_ground);
  EXPECT_FALSE(loop.ground.state.crashed);
  EXPECT_NEAR(loop.p_W_m().z(), 0.0, 0.01);
  // Disarmed: the ESC frames carry zeros, the rotors stop.
  for (double w : loop.ground.state.rotor_speed_radps) EXPECT_LT(w, 1.0);
}

TEST(ClosedLoop, CommandLinkLossHoldsThenReturnsHomeOnlyWhenHeartbeatsStop) {
  ClosedLoop loop;
  take_off(loop, 10.0);
  loop.ground.command(Cmd::GOTO, 30.0, 20.0, 15.0);
  loop.run_until(30.0);
  EXPECT_EQ(loop.ground.max_failsafe_seen, kFailsafeNone);  // heartbeats flowing: no failsafe
  loop.ground.heartbeats = false;
  const double silent_from = loop.now_s();
  ASSERT_TRUE(loop.run_until_true([&] { return loop.ground.last_status().failsafe == kFailsafeLinkLoss; },
                                  silent_from + 5.0));
  const double fired_after = loop.now_s() - silent_from;
  std::cout << "link loss: failsafe after " << fired_after << " s of silence\n";
  EXPECT_GT(fired_after, 3.0 - 0.2);  // link_loss_hold_s = 3 (last heartbeat up to 0.2 s before)
  EXPECT_LT(fired_after, 3.0 + 0.3);
  EXPECT_EQ(loop.ground.last_status().mode, kHold);
  ASSERT_TRUE(loop.run_until_true([&] { return loop.ground.last_status().mode == kReturnHome; },
                                  silent_from + 15.0));
  EXPECT_NEAR(loop.now_s() - silent_from, 13.0, 0.5);  // then link_loss_return_s = 10 more: return
  loop.run_until(loop.now_s() + 50.0);
  EXPECT_EQ(loop.ground.last_status().mode, kDisarmed);  // landed at home
  EXPECT_LT(loop.p_W_m().head<2>().norm(), 2.0);
  EXPECT_TRUE(loop.ground.state.on_ground);
}

TEST(ClosedLoop, LowBatteryReturnsThenLandsWhereItIs) {
  LoopOptions o;
  o.initial_battery_pct = 28.0;
  o.tune = [](FcParams& p) { p.failsafe.low_battery_land_pct = 24.0; };
  ClosedLoop loop(o);
  double reading_at_return = -1.0, t_return = -1.0, t_land = -1.0;
  Eigen::Vector3d p_land = Eigen::Vector3d::Zero();
  bool failsafe_before_threshold = false;
  loop.ground.on_status = [&](const Status& s) {
    if (s.battery_pct > 25.0 && s.failsafe != kFailsafeNone) failsafe_before_threshold = true;
    if (t_return < 0 && s.mode == kReturnHome) {
      t_return = s.utime_us * 1e-6;
      reading_at_return = s.battery_pct;
    }
    if (t_land < 0 && s.mode == kLand) {
      t_land = s.utime_us * 1e-6;
      p_land = {s.p_W_m[0], s.p_W_m[1], s.p_W_m[2]};
    }
  };
  take_off(loop, 10.0);
  loop.ground.command(Cmd::GOTO, 60.0, 0.0, 10.0, 10.0);
  loop.run_until(150.0);
  std::cout << "low battery: return at t=" << t_return << " s (reading " << reading_at_return << " %), land at t="
            << t_land << " s at (" << p_land.transpose() << ")\n";
  EXPECT_FALSE(failsafe_before_threshold);
  ASSERT_GT(t_return, 0.0);
  EXPECT_LE(reading_at_return, 25.0);
  ASSERT_GT(t_land, t_return);
  EXPECT_GT(p_land.head<2>().norm(), 5.0);  // landed where it was, not at home
  EXPECT_EQ(loop.ground.last_status().failsafe, kFailsafeLowBattery);
  EXPECT_EQ(loop.ground.last_status().mode, kDisarmed);
  EXPECT_TRUE(loop.ground.state.on_ground);
  EXPECT_FALSE(loop.ground.state.crashed);
}

TEST(ClosedLoop, TargetOutsideTheGeofenceIsRefusedWithItsReasonAndTheEdgeIsNotCrossed) {
  LoopOptions o;
  o.fence = Geofence({{-50, -50}, {100, -50}, {100, 100}, {-50, 100}}, 0.0, 40.0);
  ClosedLoop loop(o);
  take_off(loop, 10.0);
  int32_t seq = loop.ground.command(Cmd::GOTO, 150.0, 0.0, 10.0);
  loop.run_until(loop.now_s() + 0.1);
  const Status* s = loop.ground.status_for(seq);
  ASSERT_NE(s, nullptr);
  EXPECT_FALSE(s->last_command_accepted);
  EXPECT_EQ(s->last_command_reason, "outside the geofence");
  EXPECT_EQ(loop.ground.last_status().mode, kHold);  // nothing changed the flight
  seq = loop.ground.command(Cmd::GOTO, 20.0, 0.0, 45.0);
  loop.run_until(loop.now_s() + 0.1);
  ASSERT_NE(loop.ground.status_for(seq), nullptr);
  EXPECT_EQ(loop.ground.status_for(seq)->last_command_reason, "above the altitude limit");
  // A target 6 m inside the edge approached at 10 m/s: it brakes and never crosses, no failsafe.
  seq = loop.ground.command(Cmd::GOTO, 94.0, 0.0, 10.0, 10.0);
  double max_x = 0.0;
  loop.ground.on_state = [&](const a3lcm::vehicle_state_t& st) { max_x = std::max(max_x, st.p_W_m[0]); };
  loop.run_until(loop.now_s() + 25.0);
  ASSERT_NE(loop.ground.status_for(seq), nullptr);
  EXPECT_TRUE(loop.ground.status_for(seq)->last_command_accepted);
  std::cout << "geofence: closest approach to the edge at x = 100 m: " << 100.0 - max_x << " m\n";
  EXPECT_LT(max_x, 100.0);
  EXPECT_EQ(loop.ground.max_failsafe_seen, kFailsafeNone);
}

TEST(ClosedLoop, PushedOutOfTheGeofenceByWindItReturns) {
  LoopOptions o;
  // A wind the Iris cannot hold against (its tilt limit gives ~8.5 N; 20 m/s of drag is more):
  // it drifts east through the fence's east edge, 15 m away.
  o.mean_wind_W_mps = dynamics::wind_from_report(20.0, 270.0);
  o.fence = Geofence({{-200, -100}, {15, -100}, {15, 100}, {-200, 100}}, 0.0, 100.0);
  ClosedLoop loop(o);
  double x_at_failsafe = 0.0;
  loop.ground.on_status = [&](const Status& s) {
    if (s.failsafe == kFailsafeGeofence && x_at_failsafe == 0.0) x_at_failsafe = s.p_W_m[0];
  };
  loop.run_until(1.0);
  const int32_t seq = loop.ground.command(Cmd::TAKEOFF, 0, 0, 10.0);
  loop.run_until(1.1);
  ASSERT_NE(loop.ground.status_for(seq), nullptr);
  ASSERT_TRUE(loop.ground.status_for(seq)->last_command_accepted);
  // Inside the fence: no failsafe, however hard the wind pushes.
  ASSERT_TRUE(loop.run_until_true([&] { return loop.p_W_m().x() > 14.0; }, 40.0)) << "x = " << loop.p_W_m().x();
  EXPECT_EQ(loop.ground.max_failsafe_seen, kFailsafeNone);
  ASSERT_TRUE(loop.run_until_true([&] { return loop.ground.last_status().failsafe == kFailsafeGeofence; },
                                  loop.now_s() + 20.0))
      << "x = " << loop.p_W_m().x();
  std::cout << "geofence failsafe at estimated x = " << x_at_failsafe << " m (edge at 15 m), t = " << loop.now_s()
            << " s\n";
  EXPECT_GT(x_at_failsafe, 15.0);
  EXPECT_LT(x_at_failsafe, 17.0);
  EXPECT_EQ(loop.ground.last_status().mode, kReturnHome);
}

TEST(ClosedLoop, BadCommandsAreRefusedNotCrashed) {
  ClosedLoop loop;
  loop.run_until(1.0);
  int32_t seq = loop.ground.command(Cmd::GOTO, 10, 0, 10);
  int32_t nan_seq = loop.ground.command(Cmd::TAKEOFF, 0, 0, std::nan(""));
  int32_t unknown_seq = loop.ground.command(int8_t{42});
  loop.run_until(1.2);
  ASSERT_NE(loop.ground.status_for(seq), nullptr);
  EXPECT_EQ(loop.ground.status_for(seq)->last_command_reason, "not armed");
  ASSERT_NE(loop.ground.status_for(nan_seq), nullptr);
  EXPECT_EQ(loop.ground.status_for(nan_seq)->last_command_reason, "invalid argument");
  ASSERT_NE(loop.ground.status_for(unknown_seq), nullptr);
  EXPECT_EQ(loop.ground.status_for(unknown_seq)->last_command_reason, "unknown command");
  EXPECT_EQ(loop.bridge().counters().get("commands_nonfinite"), 1u);
  EXPECT_EQ(loop.fc().counters().get("commands_refused"), 3u);
  EXPECT_EQ(loop.ground.last_status().mode, kDisarmed);
}

}  // namespace
}  // namespace a3::bridge
