// The flight controller's logic flying the simulated vehicle directly (no CAN): take-off and
// hold, go-to, land, and each failsafe.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/fc/direct_loop.hpp"

namespace a3::bridge {
namespace {

using a3::test::DirectLoop;

FlightCommand takeoff(double z) {
  FlightCommand c;
  c.kind = FlightCommandKind::kTakeoff;
  c.target_W_m = {0, 0, z};
  return c;
}

FlightCommand go_to(double x, double y, double z, double speed = 0.0) {
  FlightCommand c;
  c.kind = FlightCommandKind::kGoto;
  c.target_W_m = {x, y, z};
  c.speed_limit_mps = speed;
  return c;
}

FlightCommand simple(FlightCommandKind kind) {
  FlightCommand c;
  c.kind = kind;
  return c;
}

double altitude_rms_error(DirectLoop& loop, double target, double from_s, double to_s) {
  double sum = 0.0;
  int n = 0;
  loop.run_until(to_s, [&](double t) {
    if (t < from_s) return;
    const double e = loop.vehicle().state().p_W_m.z() - target;
    sum += e * e;
    ++n;
  });
  return std::sqrt(sum / n);
}

class FlightControllerTest : public ::testing::Test {
 protected:
  dynamics::VehicleParams vehicle_ = dynamics::default_vehicle_params();
};

TEST_F(FlightControllerTest, TakesOffAndHoldsInStillAir) {
  DirectLoop loop(vehicle_, a3::test::fc_params_for(vehicle_));
  loop.run_until(1.0);  // sensors settle, estimator initialises
  const auto r = loop.command(takeoff(10.0));
  ASSERT_TRUE(r.accepted) << r.reason;
  loop.run_until(15.0);
  EXPECT_EQ(loop.fc().status().mode, FcMode::kHold);
  const double rms = altitude_rms_error(loop, 10.0, 15.0, 35.0);
  std::cout << "hold at 10 m, still air: altitude RMS error " << rms << " m\n";
  EXPECT_LE(rms, 0.1);
  EXPECT_LT(loop.vehicle().state().p_W_m.head<2>().norm(), 0.5);
}

TEST_F(FlightControllerTest, HoldsInEightMetrePerSecondWindWithTurbulence) {
  DirectLoop loop(vehicle_, a3::test::fc_params_for(vehicle_), dynamics::wind_from_report(8.0, 240.0), 3);
  loop.run_until(1.0);
  ASSERT_TRUE(loop.command(takeoff(10.0)).accepted);
  loop.run_until(20.0);
  const double rms = altitude_rms_error(loop, 10.0, 20.0, 50.0);
  std::cout << "hold at 10 m, 8 m/s wind with turbulence: altitude RMS error " << rms << " m\n";
  EXPECT_LE(rms, 0.5);
  EXPECT_LT(loop.vehicle().state().p_W_m.head<2>().norm(), 3.0);
}

TEST_F(FlightControllerTest, FiftyMetreGoToSettlesWithoutOvershoot) {
  DirectLoop loop(vehicle_, a3::test::fc_params_for(vehicle_));
  loop.run_until(1.0);
  ASSERT_TRUE(loop.command(takeoff(10.0)).accepted);
  loop.run_until(12.0);
  ASSERT_TRUE(loop.command(go_to(50.0, 0.0, 10.0, 6.0)).accepted);
  double max_x = 0.0;
  loop.run_until(40.0, [&](double) { max_x = std::max(max_x, loop.vehicle().state().p_W_m.x()); });
  const double overshoot = (max_x - 50.0) / 50.0;
  std::cout << "50 m go-to: overshoot " << overshoot * 100 << " %, final error "
            << std::abs(loop.vehicle().state().p_W_m.x() - 50.0) << " m\n";
  EXPECT_LE(overshoot, 0.10);
  EXPECT_NEAR(loop.vehicle().state().p_W_m.x(), 50.0, 0.05 * 50.0);
  EXPECT_EQ(loop.fc().status().mode, FcMode::kHold);  // arrived
}

TEST_F(FlightControllerTest, LandEndsDisarmedOnTheGround) {
  DirectLoop loop(vehicle_, a3::test::fc_params_for(vehicle_));
  loop.run_until(1.0);
  ASSERT_TRUE(loop.command(takeoff(8.0)).accepted);
  loop.run_until(10.0);
  ASSERT_TRUE(loop.command(simple(FlightCommandKind::kLand)).accepted);
  loop.run_until(30.0);
  EXPECT_EQ(loop.fc().status().mode, FcMode::kDisarmed);
  EXPECT_FALSE(loop.fc().status().armed);
  EXPECT_TRUE(loop.vehicle().on_ground());
  EXPECT_FALSE(loop.vehicle().crashed());
  EXPECT_NEAR(loop.vehicle().state().p_W_m.z(), 0.0, 1e-3);
}

TEST_F(FlightControllerTest, CommandLinkLossHoldsThenReturnsHome) {
  DirectLoop loop(vehicle_, a3::test::fc_params_for(vehicle_));
  loop.run_until(1.0);
  ASSERT_TRUE(loop.command(takeoff(10.0)).accepted);
  loop.run_until(10.0);
  ASSERT_TRUE(loop.command(go_to(30.0, 20.0, 15.0)).accepted);
  loop.run_until(25.0);
  EXPECT_EQ(loop.fc().status().failsafe, FcFailsafe::kNone);  // heartbeats: no failsafe
  loop.heartbeats = false;
  loop.run_until(29.0);  // 3 s without a heartbeat: hold
  EXPECT_EQ(loop.fc().status().failsafe, FcFailsafe::kLinkLoss);
  EXPECT_EQ(loop.fc().status().mode, FcMode::kHold);
  loop.run_until(40.0);  // and 10 s more: return home
  EXPECT_EQ(loop.fc().status().mode, FcMode::kReturnHome);
  loop.run_until(100.0);
  EXPECT_EQ(loop.fc().status().mode, FcMode::kDisarmed);  // landed at home
  EXPECT_LT(loop.vehicle().state().p_W_m.head<2>().norm(), 2.0);
  EXPECT_TRUE(loop.vehicle().on_ground());
}

TEST_F(FlightControllerTest, LowBatteryReturnsThenLands) {
  DirectLoop loop(vehicle_, a3::test::fc_params_for(vehicle_));
  loop.run_until(1.0);
  ASSERT_TRUE(loop.command(takeoff(10.0)).accepted);
  loop.run_until(10.0);
  ASSERT_TRUE(loop.command(go_to(40.0, 0.0, 10.0)).accepted);
  loop.run_until(20.0);
  EXPECT_EQ(loop.fc().status().failsafe, FcFailsafe::kNone);
  loop.battery_offset_pct = 76.0;  // reading drops below 25 %
  loop.run_until(21.0);
  EXPECT_EQ(loop.fc().status().failsafe, FcFailsafe::kLowBattery);
  EXPECT_EQ(loop.fc().status().mode, FcMode::kReturnHome);
  loop.battery_offset_pct = 90.0;  // below 12 %: land where it is
  loop.run_until(22.0);
  EXPECT_EQ(loop.fc().status().mode, FcMode::kLand);
  loop.run_until(50.0);
  EXPECT_EQ(loop.fc().status().mode, FcMode::kDisarmed);
}

TEST_F(FlightControllerTest, GeofenceAndAltitudeEnvelope) {
  FcParams p = a3::test::fc_params_for(vehicle_);
  p.fence = Geofence({{-50, -50}, {100, -50}, {100, 100}, {-50, 100}}, 0.0, 40.0);
  DirectLoop loop(vehicle_, p);
  loop.run_until(1.0);
  auto r = loop.command(takeoff(60.0));
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.refusal, FcRefusal::kAboveAltitudeLimit);
  ASSERT_TRUE(loop.command(takeoff(10.0)).accepted);
  loop.run_until(10.0);
  r = loop.command(go_to(150.0, 0.0, 10.0));
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.refusal, FcRefusal::kOutsideGeofence);
  EXPECT_NE(r.reason.find("geofence"), std::string::npos) << r.reason;
  EXPECT_EQ(loop.fc().status().last_reason, r.reason);
  r = loop.command(go_to(98.0, 0.0, 10.0));  // inside, but within the 5 m margin
  EXPECT_FALSE(r.accepted);
  r = loop.command(go_to(20.0, 0.0, 45.0));
  EXPECT_EQ(r.refusal, FcRefusal::kAboveAltitudeLimit);
  // A target 6 m inside the edge, approached at speed: it brakes and never crosses.
  ASSERT_TRUE(loop.command(go_to(94.0, 0.0, 10.0, 10.0)).accepted);
  double max_x = 0.0;
  loop.run_until(40.0, [&](double) { max_x = std::max(max_x, loop.vehicle().state().p_W_m.x()); });
  EXPECT_LT(max_x, 100.0);
  EXPECT_EQ(loop.fc().status().failsafe, FcFailsafe::kNone);
}

TEST_F(FlightControllerTest, BadCommandsAreRefusedWithReasons) {
  DirectLoop loop(vehicle_, a3::test::fc_params_for(vehicle_));
  // Before the estimator has a fix.
  auto r = loop.command(takeoff(10.0));
  EXPECT_EQ(r.refusal, FcRefusal::kNoPositionFix);
  loop.run_until(1.0);
  r = loop.command(go_to(10.0, 0.0, 10.0));
  EXPECT_EQ(r.refusal, FcRefusal::kNotArmed);
  r = loop.command(takeoff(std::nan("")));
  EXPECT_EQ(r.refusal, FcRefusal::kBadValue);
  ASSERT_TRUE(loop.command(takeoff(10.0)).accepted);
  loop.run_until(8.0);
  r = loop.command(go_to(std::numeric_limits<double>::infinity(), 0.0, 10.0));
  EXPECT_EQ(r.refusal, FcRefusal::kBadValue);
  r = loop.command(simple(FlightCommandKind::kDisarm));
  EXPECT_EQ(r.refusal, FcRefusal::kInFlight);
  FlightCommand speed = simple(FlightCommandKind::kSetSpeed);
  speed.speed_limit_mps = -1;
  EXPECT_EQ(loop.command(speed).refusal, FcRefusal::kBadValue);
  EXPECT_EQ(loop.fc().status().mode, FcMode::kHold);  // nothing changed the flight
  // Emergency stop cuts the motors.
  EXPECT_TRUE(loop.command(simple(FlightCommandKind::kEmergencyStop)).accepted);
  EXPECT_EQ(loop.command(go_to(5.0, 0.0, 10.0)).refusal, FcRefusal::kEmergencyStopped);
  loop.run_until(12.0);
  EXPECT_FALSE(loop.fc().status().armed);
  EXPECT_TRUE(loop.vehicle().on_ground());
}

}  // namespace
}  // namespace a3::bridge
