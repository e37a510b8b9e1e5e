// Return home as path following: the home-bound leg is the line from where the return began
// to home, held with go-to's cross-track correction, so a return in a steady crosswind stays on
// it (and clear of the zones the gate checked that line against), where pointing at home
// (cross_track_p = 0) drifts off it. Both the commanded return and the link-loss failsafe's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "tests/fc/direct_loop.hpp"

namespace a3::bridge {
namespace {

using a3::test::DirectLoop;

constexpr double kAltitude_m = 10.0;
constexpr double kCruise_mps = 8.0;  // the missions' cruise speed (agent/mission/mission.hpp)

// Distance of p from the line through a and b (horizontal), m.
double distance_from_line_m(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d u = (b - a).normalized();
  const Eigen::Vector2d d = p - a;
  return std::abs(u.x() * d.y() - u.y() * d.x());
}

struct ReturnFlight {
  Eigen::Vector2d start_W_m = Eigen::Vector2d::Zero();  // where the fc says the return began
  double max_off_line_m = 0.0;                          // from the line start → home, while returning
  double home_error_m = -1.0;                           // horizontal, once landed
  bool landed = false;
};

class ReturnHomePathFollowingTest : public ::testing::Test {
 protected:
  FcParams params(bool cross_track_correction) const {
    FcParams p = a3::test::fc_params_for(vehicle_);
    if (!cross_track_correction) p.go_to.cross_track_p = 0.0;
    return p;
  }

  // Takes off at the origin and flies to `away` at 8 m/s; then returns home, by command or,
  // with link_loss, by the failsafe (heartbeats stop: hold after 3 s, return 10 s later).
  ReturnFlight fly_out_and_home(bool cross_track_correction, const Eigen::Vector2d& away, bool link_loss) {
    DirectLoop loop(vehicle_, params(cross_track_correction), dynamics::wind_from_report(7.0, 0.0), 1, false);
    loop.run_until(1.0);
    FlightCommand takeoff;
    takeoff.kind = FlightCommandKind::kTakeoff;
    takeoff.target_W_m = {0, 0, kAltitude_m};
    EXPECT_TRUE(loop.command(takeoff).accepted);
    loop.run_until(15.0);
    FlightCommand go;
    go.kind = FlightCommandKind::kGoto;
    go.target_W_m = {away.x(), away.y(), kAltitude_m};
    go.speed_limit_mps = kCruise_mps;
    EXPECT_TRUE(loop.command(go).accepted);
    loop.run_until(loop.time_s() + away.norm() / kCruise_mps + 20.0);
    EXPECT_EQ(loop.fc().status().mode, FcMode::kHold);
    if (link_loss) {
      loop.heartbeats = false;
    } else {
      FlightCommand home;
      home.kind = FlightCommandKind::kReturnHome;
      EXPECT_TRUE(loop.command(home).accepted);
    }
    ReturnFlight f;
    bool returning = false;
    loop.run_until(loop.time_s() + away.norm() / kCruise_mps + 90.0, [&](double) {
      const FlightStatus& s = loop.fc().status();
      if (s.mode == FcMode::kReturnHome && !returning) {
        returning = true;
        f.start_W_m = s.p_W_m.head<2>();
      }
      if (s.mode != FcMode::kReturnHome) return;
      const Eigen::Vector2d p = loop.vehicle().state().p_W_m.head<2>();
      f.max_off_line_m = std::max(f.max_off_line_m, distance_from_line_m(p, f.start_W_m, Eigen::Vector2d::Zero()));
    });
    f.landed = loop.fc().status().mode == FcMode::kDisarmed;
    f.home_error_m = loop.vehicle().state().p_W_m.head<2>().norm();
    EXPECT_TRUE(returning);
    return f;
  }

  dynamics::VehicleParams vehicle_ = dynamics::default_vehicle_params();
};

// 7 m/s from the north across a 200 m return west: within 1 m of the line with the correction,
// more than 1 m off it when the fc points at home.
TEST_F(ReturnHomePathFollowingTest, TheCommandedReturnHoldsItsLineInASteadyCrosswind) {
  const ReturnFlight with = fly_out_and_home(true, {200.0, 0.0}, false);
  const ReturnFlight without = fly_out_and_home(false, {200.0, 0.0}, false);
  std::cout << "return home 200 m west at 8 m/s, steady 7 m/s crosswind: max off the line " << with.max_off_line_m
            << " m (without the correction " << without.max_off_line_m << " m), landed " << with.home_error_m
            << " m from home\n";
  EXPECT_LE(with.max_off_line_m, 1.0);
  EXPECT_GT(without.max_off_line_m, 1.0);  // the bound discriminates
  EXPECT_TRUE(with.landed);
  EXPECT_LE(with.home_error_m, 1.5);
}

// The link-loss failsafe's return from (150, 60), where the vehicle held when the link went:
// the line runs from there, not from wherever the wind had pushed it during the climb.
TEST_F(ReturnHomePathFollowingTest, TheFailsafeReturnHoldsTheLineFromWhereItBegan) {
  const ReturnFlight with = fly_out_and_home(true, {150.0, 60.0}, true);
  const ReturnFlight without = fly_out_and_home(false, {150.0, 60.0}, true);
  std::cout << "link-loss return home from (150, 60), steady 7 m/s wind from the north: max off the line "
            << with.max_off_line_m << " m (without the correction " << without.max_off_line_m << " m)\n";
  EXPECT_LE((with.start_W_m - Eigen::Vector2d(150.0, 60.0)).norm(), 1.0);
  EXPECT_LE(with.max_off_line_m, 1.0);
  EXPECT_GT(without.max_off_line_m, 1.0);
  EXPECT_TRUE(with.landed);
}

}  // namespace
}  // namespace a3::bridge
