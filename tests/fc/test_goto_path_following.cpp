// Go-to as path following (issue 15): a 300 m leg at cruise speed holds its line in a steady
// crosswind and in gusts, where pointing at the target (cross_track_p = 0, the behaviour before)
// drifts off it; a leg begun off its line converges back; arrival is unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "common/json_file.hpp"
#include "tests/fc/direct_loop.hpp"
#include "tests/test_support.hpp"

namespace a3::bridge {
namespace {

using a3::test::DirectLoop;

constexpr double kAltitude_m = 10.0;
constexpr double kCruise_mps = 8.0;  // the missions' cruise speed (agent/mission/mission.hpp)

FlightCommand go_to(double x, double y, double speed_mps) {
  FlightCommand c;
  c.kind = FlightCommandKind::kGoto;
  c.target_W_m = {x, y, kAltitude_m};
  c.speed_limit_mps = speed_mps;
  return c;
}

struct LegFlight {
  double max_cross_track_m = 0.0;  // over the whole leg, until it holds at the target
  double max_overshoot_m = 0.0;    // past the target along the leg
  double final_error_m = 0.0;
  bool arrived = false;
};

class GotoPathFollowingTest : public ::testing::Test {
 protected:
  FcParams params(bool cross_track_correction) const {
    FcParams p = a3::test::fc_params_for(vehicle_);
    if (!cross_track_correction) p.go_to.cross_track_p = 0.0;
    return p;
  }
  // Takes off to 10 m at the origin, then flies one leg east to (length_m, 0).
  LegFlight fly_east_leg(bool cross_track_correction, const Eigen::Vector3d& wind_W_mps, bool gusts, uint64_t seed,
                         double length_m = 300.0) {
    DirectLoop loop(vehicle_, params(cross_track_correction), wind_W_mps, seed, gusts);
    loop.run_until(1.0);
    FlightCommand takeoff;
    takeoff.kind = FlightCommandKind::kTakeoff;
    takeoff.target_W_m = {0, 0, kAltitude_m};
    EXPECT_TRUE(loop.command(takeoff).accepted);
    loop.run_until(20.0);
    EXPECT_EQ(loop.fc().status().mode, FcMode::kHold);
    EXPECT_TRUE(loop.command(go_to(length_m, 0.0, kCruise_mps)).accepted);
    LegFlight f;
    const double end_s = loop.time_s() + length_m / kCruise_mps + 30.0;
    loop.run_until(end_s, [&](double) {
      const Eigen::Vector3d& p = loop.vehicle().state().p_W_m;
      f.max_cross_track_m = std::max(f.max_cross_track_m, std::abs(p.y()));
      f.max_overshoot_m = std::max(f.max_overshoot_m, p.x() - length_m);
    });
    f.final_error_m = (loop.vehicle().state().p_W_m - Eigen::Vector3d(length_m, 0, kAltitude_m)).norm();
    f.arrived = loop.fc().status().mode == FcMode::kHold;
    return f;
  }

  dynamics::VehicleParams vehicle_ = dynamics::default_vehicle_params();
};

// 7 m/s across an 8 m/s leg: the drag then asks for about 3.1 m/s² along and 2.7 m/s² across,
// near the fc's 4 m/s² horizontal limit and beyond the 2 m/s² its velocity integral may give
// per axis, so pointing at the target leaves a standing drift across. Bound: 1 m.
TEST_F(GotoPathFollowingTest, HoldsA300MetreLegInASteadyCrosswind) {
  const Eigen::Vector3d wind = dynamics::wind_from_report(7.0, 0.0);  // from the north, across the leg
  const LegFlight with = fly_east_leg(true, wind, false, 1);
  const LegFlight without = fly_east_leg(false, wind, false, 1);
  std::cout << "300 m at 8 m/s, steady 7 m/s crosswind: max cross-track " << with.max_cross_track_m
            << " m (without the correction " << without.max_cross_track_m << " m)\n";
  EXPECT_LE(with.max_cross_track_m, 1.0);
  EXPECT_GT(without.max_cross_track_m, 1.0);  // the bound discriminates
  EXPECT_TRUE(with.arrived);
}

// 6 m/s mean with Dryden turbulence (σ about 1.1 m/s along and across at the loop's reference
// height): a gust must not push the track more than 1.5 m off the line. At 7 m/s mean the drag
// alone nears the acceleration limit, so no controller of this vehicle could promise a bound.
TEST_F(GotoPathFollowingTest, HoldsA300MetreLegInGusts) {
  const Eigen::Vector3d wind = dynamics::wind_from_report(6.0, 0.0);
  double worst_without_m = 0.0;
  for (const uint64_t seed : {1u, 3u}) {
    const LegFlight with = fly_east_leg(true, wind, true, seed);
    const LegFlight without = fly_east_leg(false, wind, true, seed);
    std::cout << "300 m at 8 m/s, 6 m/s wind with gusts, seed " << seed << ": max cross-track "
              << with.max_cross_track_m << " m (without the correction " << without.max_cross_track_m << " m)\n";
    EXPECT_LE(with.max_cross_track_m, 1.5) << "seed " << seed;
    EXPECT_TRUE(with.arrived) << "seed " << seed;
    worst_without_m = std::max(worst_without_m, without.max_cross_track_m);
  }
  EXPECT_GT(worst_without_m, 1.5);  // the bound discriminates
}

// A go-to that replaces one in progress continues from that one's target: here the vehicle is
// still at the origin, 20 m off the new leg (0, 20) → (200, 20), and converges onto it.
TEST_F(GotoPathFollowingTest, ALegBegunOffItsLineConvergesOntoIt) {
  for (const bool on : {true, false}) {
    DirectLoop loop(vehicle_, params(on));
    loop.run_until(1.0);
    FlightCommand takeoff;
    takeoff.kind = FlightCommandKind::kTakeoff;
    takeoff.target_W_m = {0, 0, kAltitude_m};
    ASSERT_TRUE(loop.command(takeoff).accepted);
    loop.run_until(15.0);
    ASSERT_TRUE(loop.command(go_to(0.0, 20.0, kCruise_mps)).accepted);
    loop.run_until(15.1);
    ASSERT_TRUE(loop.command(go_to(200.0, 20.0, kCruise_mps)).accepted);
    EXPECT_EQ(loop.fc().goto_path().start_W_m(), Eigen::Vector2d(0.0, 20.0));
    double error_at_100_m = -1.0;
    double worst_after_100_m = 0.0;
    loop.run_until(60.0, [&](double) {
      const Eigen::Vector3d& p = loop.vehicle().state().p_W_m;
      const double error_m = std::abs(p.y() - 20.0);
      if (p.x() >= 100.0 && error_at_100_m < 0.0) error_at_100_m = error_m;
      if (p.x() >= 100.0) worst_after_100_m = std::max(worst_after_100_m, error_m);
    });
    std::cout << "20 m off the line, cross-track " << (on ? "on" : "off") << ": " << error_at_100_m
              << " m off it half-way, at most " << worst_after_100_m << " m after\n";
    if (on) {
      EXPECT_LE(worst_after_100_m, 0.5);
      EXPECT_EQ(loop.fc().status().mode, FcMode::kHold);  // and it arrived
    } else {
      EXPECT_GT(error_at_100_m, 5.0);  // pointing at the target cuts the corner
    }
  }
}

// Arrival as before: stop at the target, in still air and in a crosswind, without more
// overshoot than pointing at the target gives.
TEST_F(GotoPathFollowingTest, ArrivalIsUnchanged) {
  for (const double wind_mps : {0.0, 5.0}) {
    const Eigen::Vector3d wind = dynamics::wind_from_report(wind_mps, 0.0);
    const LegFlight with = fly_east_leg(true, wind, false, 1);
    const LegFlight without = fly_east_leg(false, wind, false, 1);
    std::cout << "300 m at 8 m/s, wind " << wind_mps << " m/s: overshoot " << with.max_overshoot_m
              << " m (pointing at the target " << without.max_overshoot_m << " m), final error " << with.final_error_m
              << " m\n";
    EXPECT_TRUE(with.arrived);
    EXPECT_LE(with.max_overshoot_m, without.max_overshoot_m + 0.1);
    EXPECT_LE(with.final_error_m, 0.5);
  }
}

// The goto section of bridge/fc/fc_params.default.json holds the code's defaults.
TEST(GotoParams, TheDefaultFileHoldsTheCodesDefaults) {
  const auto path = a3::test::source_dir() / "bridge/fc/fc_params.default.json";
  FcParams odd;
  odd.go_to = FcGotoParams{9, 9, 99, 99};
  const FcParams p = fc_params_from_json(common::load_json_file(path), path.string(), odd);
  const FcGotoParams d;
  EXPECT_EQ(p.go_to.cross_track_p, d.cross_track_p);
  EXPECT_EQ(p.go_to.cross_track_i, d.cross_track_i);
  EXPECT_EQ(p.go_to.max_cross_track_speed_mps, d.max_cross_track_speed_mps);
  EXPECT_EQ(p.go_to.along_track_accel_mps2, d.along_track_accel_mps2);
  EXPECT_THROW(fc_params_from_json(nlohmann::json::parse(R"({"goto": {"cross_track_p": -1}})"), "fc.json"),
               common::InputError);
}

}  // namespace
}  // namespace a3::bridge
