// What the agent is told about the wind (issue 15's leftovers): read_telemetry's wind estimate
// and the ground speed made good along the current leg, collision_avoidance's own track with
// the ground speed and wind it assumed, and the weather update's onboard estimate. On the fake
// flight controller (no accelerometer: the wind stays the forecast of the test config, 6 m/s
// from 240°, i.e. blowing toward east-north-east, (5.196, 3.0) m/s ENU). Flying west, the Iris
// (10.498 m/s of air speed at the fc's 4 m/s² clamp) makes good
// −5.196 + sqrt(10.498² − 3²) = 4.86 m/s of a commanded 9.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "tests/vehicle/vehicle_test_util.hpp"
#include "vehicle/wind_estimator.hpp"
#include "vehicle/wind_reports.hpp"

namespace a3::vehicle {
namespace {

using test::a2a;
using test::mcp;
using test::Rig;

constexpr double kIrisAirspeed_mps = 10.498;
constexpr double kHeadwindWest_mps = 5.196;  // the test wind's component against a westward course
constexpr double kCrosswindWest_mps = 3.0;
const double kWestGroundSpeed_mps =
    std::sqrt(kIrisAirspeed_mps * kIrisAirspeed_mps - kCrosswindWest_mps * kCrosswindWest_mps) - kHeadwindWest_mps;

const nlohmann::json kForecastWind = {{"speed_mps", 6.0}, {"from_deg", 240.0}, {"source", "forecast"},
                                      {"learned_s", 0.0}, {"age_s", nullptr}};

// Takes off at home (20, 20), flies to (360, 20, 40), then starts a route back west at 9 m/s
// and lets it fly 2 s.
void fly_west_leg(Rig& rig) {
  rig.take_off(40.0);
  rig.fly_to(Eigen::Vector3d(360, 20, 40));
  const auto r = rig.result(mcp("navigate_to", {{"waypoints", {{40, 20, 40}}}, {"speed_mps", 9.0}}));
  ASSERT_EQ(r.value("status", ""), "accepted") << r.dump();
  rig.run_for(2.0);
}

TEST(WindReports, TelemetryGivesTheForecastSeededWindAndNoLegOnTheGround) {
  Rig rig;
  const auto t = rig.result(mcp("read_telemetry"));
  EXPECT_EQ(t["wind"], kForecastWind) << t.dump();
  EXPECT_TRUE(t["leg"].is_null()) << t.dump();
  const auto only = rig.result(mcp("read_telemetry", {{"fields", {"wind", "leg"}}}));
  EXPECT_EQ(only.size(), 2u) << only.dump();
}

TEST(WindReports, TelemetryGivesTheGroundSpeedMadeGoodAlongTheRoutesLeg) {
  Rig rig;
  fly_west_leg(rig);
  const auto t = rig.result(mcp("read_telemetry"));
  const auto& leg = t["leg"];
  ASSERT_TRUE(leg.is_object()) << t.dump();
  EXPECT_EQ(leg["kind"], "route");
  EXPECT_EQ(leg["target"], (nlohmann::json{{"x", 40.0}, {"y", 20.0}, {"z", 40.0}}));
  EXPECT_NEAR(std::abs(leg["course_deg"].get<double>()), 180.0, 0.1) << leg.dump();
  EXPECT_EQ(leg["commanded_speed_mps"], 9.0);
  EXPECT_NEAR(leg["ground_speed_mps"].get<double>(), kWestGroundSpeed_mps, 0.01) << leg.dump();  // 4.86, not 9
  EXPECT_NEAR(leg["headwind_mps"].get<double>(), kHeadwindWest_mps, 0.01) << leg.dump();
  // Flying west, the wind's 3 m/s northward is from the left: negative.
  EXPECT_NEAR(leg["crosswind_mps"].get<double>(), -kCrosswindWest_mps, 0.01) << leg.dump();
  EXPECT_NEAR(leg["eta_s"].get<double>(), leg["distance_m"].get<double>() / kWestGroundSpeed_mps, 0.1) << leg.dump();
  EXPECT_EQ(t["wind"], kForecastWind);
}

TEST(WindReports, TelemetryDuringTheReturnHomeGivesTheLegHome) {
  Rig rig;
  rig.take_off(40.0);
  rig.fly_to(Eigen::Vector3d(360, 20, 40));
  const auto r = rig.result(mcp("return_to_home"));
  ASSERT_EQ(r.value("route", ""), "direct") << r.dump();
  rig.run_for(1.0);
  const auto t = rig.result(mcp("read_telemetry"));
  const auto& leg = t["leg"];
  ASSERT_TRUE(leg.is_object()) << t.dump();
  EXPECT_EQ(leg["kind"], "return_home");
  EXPECT_EQ(leg["target"], (nlohmann::json{{"x", 20.0}, {"y", 20.0}, {"z", 0.0}}));
  EXPECT_NEAR(leg["ground_speed_mps"].get<double>(), std::min(kWestGroundSpeed_mps, 5.0), 0.01) << leg.dump();
  // The flight home in the wind plus the 40 m descent at 1 m/s.
  EXPECT_NEAR(leg["eta_s"].get<double>(), leg["distance_m"].get<double>() / kWestGroundSpeed_mps + 40.0, 0.5)
      << leg.dump();
}

TEST(WindReports, CollisionAvoidanceSaysWhatGroundSpeedAndWindItAssumedForOurTrack) {
  Rig rig;
  fly_west_leg(rig);
  const auto answer = rig.call(a2a("collision_avoidance", "uav_swarm_agent", {{"request", "query"}}));
  const auto& own = answer["payload"]["own_track"];
  ASSERT_TRUE(own.is_object()) << answer.dump();
  EXPECT_EQ(own["basis"], "route");
  EXPECT_EQ(own["commanded_speed_mps"], 9.0);
  EXPECT_NEAR(own["ground_speed_mps"].get<double>(), kWestGroundSpeed_mps, 0.01) << own.dump();
  EXPECT_EQ(own["wind"], kForecastWind);
  ASSERT_EQ(own["legs"].size(), 1u) << own.dump();
  const auto& leg = own["legs"][0];
  EXPECT_EQ(leg["to"], nlohmann::json::array({40.0, 20.0, 40.0}));
  // From the true position (the fake fc's estimate + its true offset, as of its last state, at
  // most 0.1 s old) to the waypoint at 4.86 m/s.
  const Eigen::Vector3d truth_W_m = rig.fc.position() + test::FakeFcConfig{}.true_offset_W_m;
  const double distance_m = (truth_W_m.head<2>() - Eigen::Vector2d(40, 20)).norm();
  EXPECT_NEAR(leg["arrive_in_s"].get<double>(), distance_m / kWestGroundSpeed_mps, 0.3) << own.dump();
}

TEST(WindReports, CollisionAvoidanceWhileHoldingAssumesNoTrack) {
  Rig rig;
  rig.take_off(40.0);
  const auto own = rig.call(a2a("collision_avoidance", "uav_swarm_agent"))["payload"]["own_track"];
  EXPECT_EQ(own["basis"], "hold") << own.dump();
  EXPECT_TRUE(own["ground_speed_mps"].is_null()) << own.dump();
  EXPECT_TRUE(own["legs"].empty()) << own.dump();
}

TEST(WindReports, TheWeatherUpdateGivesTheVehiclesOwnEstimateBesideTheForecast) {
  Rig rig;
  const auto answer = rig.call(a2a("request_weather_update", "weather_service"));
  EXPECT_EQ(answer["payload"]["wind_mps"], 6.0) << answer.dump();
  EXPECT_EQ(answer["payload"]["vehicle_wind"], kForecastWind) << answer.dump();
}

// The Iris's energy model in a 6 m/s wind from the north-east, (-4.243, -4.243) m/s ENU: flying
// east it meets 4.243 m/s of headwind and 4.243 m/s of crosswind from its left (it makes good
// -4.243 + sqrt(10.498^2 - 4.243^2) = 5.36 m/s); flying west the same wind is a tailwind from
// its right, and the fc holds the commanded 9 m/s over the ground.
constexpr double kDiagonal_mps = 6.0 / 1.4142135623730951;
const Eigen::Vector2d kNorthEastWind_W_mps = wind_from_report(6.0, 45.0);

EnergyModel iris_in(const Eigen::Vector2d& wind_W_mps) {
  EnergyModel energy;
  energy.ground_speed = std::make_shared<GroundSpeedModel>(AirframeLimits{}, wind_W_mps);
  return energy;
}

nlohmann::json leg_at_9(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector2d& wind_W_mps) {
  return flown_leg_json({"route", from, {to}, 9.0}, iris_in(wind_W_mps), wind_W_mps);
}

TEST(WindReports, AHeadwindLegIsSlowerThanCommandedWithTheWindsComponentsSigned) {
  const auto leg = leg_at_9({0, 0, 30}, {200, 0, 30}, kNorthEastWind_W_mps);
  const double made_good_mps =
      std::sqrt(kIrisAirspeed_mps * kIrisAirspeed_mps - kDiagonal_mps * kDiagonal_mps) - kDiagonal_mps;
  EXPECT_NEAR(leg["course_deg"].get<double>(), 0.0, 1e-9) << leg.dump();
  EXPECT_EQ(leg["distance_m"], 200.0);
  EXPECT_NEAR(leg["ground_speed_mps"].get<double>(), made_good_mps, 0.01) << leg.dump();  // 5.36 of 9
  EXPECT_NEAR(leg["headwind_mps"].get<double>(), kDiagonal_mps, 0.01) << leg.dump();
  EXPECT_NEAR(leg["crosswind_mps"].get<double>(), -kDiagonal_mps, 0.01) << leg.dump();  // from the left
  EXPECT_NEAR(leg["eta_s"].get<double>(), 200.0 / made_good_mps, 0.1) << leg.dump();
}

TEST(WindReports, ATailwindLegFliesTheCommandedSpeedWithTheWindsComponentsSigned) {
  const auto leg = leg_at_9({200, 0, 30}, {0, 0, 30}, kNorthEastWind_W_mps);
  EXPECT_NEAR(std::abs(leg["course_deg"].get<double>()), 180.0, 1e-9) << leg.dump();
  EXPECT_EQ(leg["ground_speed_mps"], 9.0) << leg.dump();  // the fc's ground velocity is capped at the command
  EXPECT_NEAR(leg["headwind_mps"].get<double>(), -kDiagonal_mps, 0.01) << leg.dump();
  EXPECT_NEAR(leg["crosswind_mps"].get<double>(), kDiagonal_mps, 0.01) << leg.dump();  // from the right
  EXPECT_NEAR(leg["eta_s"].get<double>(), 200.0 / 9.0, 0.05) << leg.dump();
}

TEST(WindReports, APureCrosswindSlowsTheLegAndHasNoHeadwind) {
  const Eigen::Vector2d from_east = wind_from_report(8.0, 90.0);  // blowing west
  const auto north = leg_at_9({0, 0, 30}, {0, 300, 30}, from_east);
  const double made_good_mps = std::sqrt(kIrisAirspeed_mps * kIrisAirspeed_mps - 64.0);  // 6.80 of 9
  EXPECT_NEAR(north["course_deg"].get<double>(), 90.0, 1e-9) << north.dump();
  EXPECT_NEAR(north["headwind_mps"].get<double>(), 0.0, 1e-9) << north.dump();
  EXPECT_NEAR(north["crosswind_mps"].get<double>(), 8.0, 1e-9) << north.dump();  // from the right
  EXPECT_NEAR(north["ground_speed_mps"].get<double>(), made_good_mps, 0.01) << north.dump();
  EXPECT_NEAR(north["eta_s"].get<double>(), 300.0 / made_good_mps, 0.1) << north.dump();
}

TEST(WindReports, AVerticalLegHasNoCourseButAnEtaAndACourseTheWindForbidsHasNoEta) {
  const auto climb = leg_at_9({10, 10, 0}, {10, 10, 40}, kNorthEastWind_W_mps);
  EXPECT_TRUE(climb["course_deg"].is_null()) << climb.dump();
  EXPECT_TRUE(climb["ground_speed_mps"].is_null()) << climb.dump();
  EXPECT_TRUE(climb["headwind_mps"].is_null()) << climb.dump();
  EXPECT_NEAR(climb["eta_s"].get<double>(), 40.0 / 2.0, 1e-9) << climb.dump();  // at climb_speed_mps
  // 11 m/s of crosswind is more than the Iris's 10.5 m/s of air speed: it cannot hold the course.
  const auto held_off = leg_at_9({0, 0, 30}, {0, 300, 30}, wind_from_report(11.0, 90.0));
  EXPECT_EQ(held_off["ground_speed_mps"], 0.0) << held_off.dump();
  EXPECT_TRUE(held_off["eta_s"].is_null()) << held_off.dump();
}

TEST(WindReports, TheReturnHomeLegClimbsFliesHomeAtTheCruiseSpeedAndDescends) {
  ToolServerConfig config = test::test_config();  // home (20, 20, 0)
  const EnergyModel energy = iris_in(Eigen::Vector2d::Zero());
  const FlownLeg home = return_home_leg({220, 20, 10}, config, 3.0, energy);
  EXPECT_EQ(home.kind, "return_home");
  EXPECT_EQ(home.commanded_speed_mps, energy.cruise_speed_mps);  // never slower than the cruise speed
  ASSERT_FALSE(home.points.empty());
  EXPECT_EQ(home.points.back(), Eigen::Vector3d(20, 20, 0));
  const auto leg = flown_leg_json(home, energy, Eigen::Vector2d::Zero());
  const double climb_m = config.gate.return_altitude_m - 10.0;
  EXPECT_NEAR(leg["eta_s"].get<double>(), climb_m / 2.0 + 200.0 / 5.0 + config.gate.return_altitude_m / 1.0, 0.1)
      << leg.dump();
}

// A vehicle flying where the tool server did not send it is predicted straight on at its velocity.
TEST(WindReports, AnOwnTrackExtrapolatedFromTheVelocityHasNoCommandedSpeed) {
  SelfView self;
  self.known = true;
  self.now_s = 10.0;
  self.basis = TrackBasis::kVelocity;
  self.v_W_mps = Eigen::Vector3d(3, 4, 0);
  self.predicted.path = {{10.0, Eigen::Vector3d(0, 0, 20)}, {70.0, Eigen::Vector3d(180, 240, 20)}};
  const WindEstimator wind(AirframeLimits{}, kNorthEastWind_W_mps);
  const auto own = own_track_json(self, iris_in(kNorthEastWind_W_mps), wind, 60.0);
  EXPECT_EQ(own["basis"], "velocity");
  EXPECT_TRUE(own["commanded_speed_mps"].is_null()) << own.dump();
  EXPECT_EQ(own["ground_speed_mps"], 5.0) << own.dump();
  ASSERT_EQ(own["legs"].size(), 1u) << own.dump();
  EXPECT_EQ(own["legs"][0]["arrive_in_s"], 60.0);
  EXPECT_EQ(own["wind"]["from_deg"], 45.0) << own.dump();
}

// Hovering in still air for 6 s (10 Hz): the estimate is learned from telemetry; its age counts
// from the last state that moved it.
TEST(WindReports, TheWindReportSaysHowLongItLearnedAndHowOldItIs) {
  WindEstimator estimate(AirframeLimits{}, wind_from_report(3.0, 0.0));
  EXPECT_FALSE(estimate.last_update_t_s().has_value());
  WindSample hover;
  hover.on_ground = false;
  hover.f_B_mps2 = Eigen::Vector3d(0, 0, 9.80665);
  for (int k = 0; k <= 60; ++k) {
    hover.t_s = 10.0 + 0.1 * k;
    estimate.add(hover);
  }
  hover.on_ground = true;  // landed: no longer moves it
  hover.t_s = 17.0;
  estimate.add(hover);
  const auto report = wind_report_json(estimate, 18.5);
  EXPECT_EQ(report["source"], "telemetry") << report.dump();
  EXPECT_NEAR(report["learned_s"].get<double>(), 6.0, 1e-9) << report.dump();
  EXPECT_NEAR(report["age_s"].get<double>(), 2.5, 1e-9) << report.dump();
  EXPECT_LT(report["speed_mps"].get<double>(), 3.0) << report.dump();  // decaying toward the still air
}

}  // namespace
}  // namespace a3::vehicle
