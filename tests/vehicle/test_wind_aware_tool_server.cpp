// The tool server's ETAs in wind, on the fake flight controller (which has no accelerometer,
// so the wind stays the forecast): navigate_to and return_to_home time their legs at the
// ground speed the Iris makes good (10.498 m/s of air speed at the fc's 4 m/s² clamp), and
// name the wind they assumed.
#include <gtest/gtest.h>

#include "tests/vehicle/vehicle_test_util.hpp"

namespace a3::vehicle {
namespace {

using test::mcp;
using test::Rig;

constexpr double kIrisAirspeed_mps = 10.498;
constexpr double kSettle_s = 3.0;  // EnergyModel::settle_s_per_waypoint

ToolServerConfig config_with_wind(double speed_mps, double from_deg) {
  ToolServerConfig c = test::test_config();
  c.env = {"clear", speed_mps, from_deg, std::nullopt};
  return c;
}

// navigate_to 300 m east at 9 m/s from (20, 20, 40): its result.
nlohmann::json navigate_east(Rig& rig) {
  rig.take_off(40.0);
  return rig.result(mcp("navigate_to", {{"waypoints", {{320, 20, 40}}}, {"speed_mps", 9.0}}));
}

TEST(WindAwareToolServer, NavigateToTimesTheLegAtTheGroundSpeedIntoTheWind) {
  Rig calm(config_with_wind(0.0, 90.0)), headwind(config_with_wind(7.0, 90.0));
  const auto c = navigate_east(calm), h = navigate_east(headwind);
  ASSERT_EQ(h.value("status", ""), "accepted") << h.dump();
  EXPECT_NEAR(c["eta_s"].get<double>(), 300.0 / 9.0 + kSettle_s, 0.06) << c.dump();
  EXPECT_NEAR(h["eta_s"].get<double>(), 300.0 / (kIrisAirspeed_mps - 7.0) + kSettle_s, 0.1) << h.dump();  // 88.8 s
  EXPECT_EQ(h["wind"], (nlohmann::json{{"speed_mps", 7.0}, {"from_deg", 90.0}, {"source", "forecast"}})) << h.dump();
  // A tailwind does not make the fc fly faster than commanded.
  Rig tailwind(config_with_wind(7.0, 270.0));
  EXPECT_NEAR(navigate_east(tailwind)["eta_s"].get<double>(), 300.0 / 9.0 + kSettle_s, 0.06);
}

TEST(WindAwareToolServer, ReturnToHomeIsTimedAgainstTheWindOnTheWayBack) {
  // Home is west of (320, 20, 40): a west wind (from 270°) is a headwind on the way back. The
  // legs: keep 40 m, fly 300 m home at 9 m/s (the route's speed), descend 40 m at 1 m/s, with
  // the settle time at each of the three.
  const auto eta_home = [](double wind_mps) {
    Rig rig(config_with_wind(wind_mps, 270.0));
    rig.take_off(40.0);
    rig.result(mcp("adjust_speed", {{"speed_mps", 9.0}}));
    rig.fly_to(Eigen::Vector3d(320, 20, 40));
    const auto r = rig.result(mcp("return_to_home"));
    EXPECT_EQ(r.value("route", ""), "direct") << r.dump();
    return r.value("eta_s", 0.0);
  };
  EXPECT_NEAR(eta_home(0.0), 300.0 / 9.0 + 40.0 + 3 * kSettle_s, 0.1);
  EXPECT_NEAR(eta_home(7.0), 300.0 / (kIrisAirspeed_mps - 7.0) + 40.0 + 3 * kSettle_s, 0.1);  // 134.8 s, not 82.3 s
}

}  // namespace
}  // namespace a3::vehicle
