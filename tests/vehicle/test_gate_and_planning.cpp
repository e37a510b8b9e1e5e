// The vehicle side's pure parts: the energy model's numbers, the safety gate's rules, orbit
// and survey patterns, the path planner, the onboard route's decisions, the swarm's closest
// approach and yield, and the scenario's sensors and weather read with errors naming the field.
#include <gtest/gtest.h>

#include <limits>

#include "tests/vehicle/vehicle_test_util.hpp"
#include "vehicle/maneuvers.hpp"
#include "vehicle/onboard_route.hpp"
#include "vehicle/path_planner.hpp"
#include "vehicle/safety_gate.hpp"
#include "vehicle/sensor_suite.hpp"
#include "vehicle/swarm_peer.hpp"
#include "vehicle/weather_service.hpp"

namespace a3::vehicle {
namespace {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

SafetyGate test_gate() { return SafetyGate(test::test_airspace(), GateConfig{}, EnergyModel{}, V3(20, 20, 0)); }

TEST(EnergyModel, CostsFollowFromPowerCapacityAndSpeed) {
  EnergyModel e;
  e.hover_power_w = 200.0;
  e.battery_capacity_wh = 50.0;  // 180 kJ: 900 s of hover
  e.cruise_power_factor = 1.0;
  e.margin_factor = 1.0;
  e.settle_s_per_waypoint = 0.0;
  EXPECT_DOUBLE_EQ(e.percent_per_s(), 100.0 / 900.0);
  EXPECT_DOUBLE_EQ(e.percent_per_m(5.0), 100.0 / 900.0 / 5.0);
  // 100 m level at 5 m/s = 20 s; 20 m up at 2 m/s = 10 s; 20 m down at 1 m/s = 20 s.
  EXPECT_DOUBLE_EQ(e.leg_time_s(V3(0, 0, 10), V3(100, 0, 10), 5.0), 20.0);
  EXPECT_DOUBLE_EQ(e.leg_time_s(V3(0, 0, 10), V3(0, 0, 30), 5.0), 10.0);
  EXPECT_DOUBLE_EQ(e.leg_time_s(V3(0, 0, 30), V3(0, 0, 10), 5.0), 20.0);
  EXPECT_NEAR(e.leg_percent(V3(0, 0, 10), V3(100, 0, 30), 5.0), 30.0 * 100.0 / 900.0, 1e-12);
  e.margin_factor = 1.5;
  e.settle_s_per_waypoint = 2.0;
  EXPECT_NEAR(e.route_percent(V3(0, 0, 10), {V3(100, 0, 10), V3(100, 100, 10)}, 5.0),
              1.5 * (40.0 + 4.0) * 100.0 / 900.0, 1e-12);
  EXPECT_NEAR(e.route_time_s(V3(0, 0, 10), {V3(100, 0, 10), V3(100, 100, 10)}, 5.0), 44.0, 1e-12);
  e.hover_power_w = -5.0;
  try {
    e.validate("energy");
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("energy.hover_power_w must be a finite number > 0"), std::string::npos);
  }
}

TEST(EnergyModel, TheReturnHomeLegsAreTheFlightControllers) {
  const auto low = return_home_legs(V3(100, 50, 12), V3(0, 0, 0), 30.0, 10.0, 120.0);
  ASSERT_EQ(low.size(), 3u);
  EXPECT_EQ(low[0], V3(100, 50, 30)) << "climbs to the return altitude";
  EXPECT_EQ(low[1], V3(0, 0, 30));
  EXPECT_EQ(low[2], V3(0, 0, 0));
  EXPECT_EQ(return_home_legs(V3(100, 50, 80), V3(0, 0, 0), 30.0, 10.0, 120.0)[1], V3(0, 0, 80)) << "keeps a higher one";
  EXPECT_EQ(return_home_legs(V3(1, 1, 20), V3(0, 0, 0), 30.0, 10.0, 25.0)[0].z(), 25.0) << "capped by the envelope";
}

TEST(SafetyGate, TargetRulesInOrder) {
  const SafetyGate gate = test_gate();
  EXPECT_EQ(gate.check_target(V3(100, 100, 40), "t"), "");
  EXPECT_EQ(gate.check_target(V3(100, 100, 120), "t"), "") << "the maximum is inside";
  EXPECT_NE(gate.check_target(V3(100, 100, 120.5), "t").find("above the envelope's maximum 120.0 m"), std::string::npos);
  EXPECT_NE(gate.check_target(V3(4, 100, 40), "t").find("4.0 m from the geofence edge"), std::string::npos);
  EXPECT_NE(gate.check_target(V3(-1, 100, 40), "t").find("outside the geofence"), std::string::npos);
  EXPECT_NE(gate.check_target(V3(320, 60, 30), "t").find("inside no-fly zone nfz-p"), std::string::npos);
  EXPECT_NE(gate.check_target(V3(320, 60, 63), "t").find("from no-fly zone nfz-p"), std::string::npos)
      << "3 m above its ceiling: inside the 5 m vertical margin";
  EXPECT_EQ(gate.check_target(V3(320, 60, 66), "t"), "") << "6 m above its ceiling";
  EXPECT_NE(gate.check_target(V3(344, 60, 40), "t").find("4.0 m from no-fly zone nfz-p"), std::string::npos)
      << "4 m off its side is too close";
  EXPECT_EQ(gate.check_target(V3(345, 60, 40), "t"), "") << "5 m off is the margin: allowed";
  EXPECT_NE(gate.check_target(V3(std::numeric_limits<double>::quiet_NaN(), 0, 40), "t").find("not a finite point"),
            std::string::npos);
}

TEST(SafetyGate, LegRules) {
  const SafetyGate gate = test_gate();
  EXPECT_EQ(gate.check_leg(V3(100, 100, 40), V3(300, 100, 40), "leg"), "") << "50 m south of the cylinder's centre";
  EXPECT_NE(gate.check_leg(V3(100, 120, 40), V3(300, 120, 40), "leg").find("nfz-c"), std::string::npos);
  EXPECT_NE(gate.check_leg(V3(100, 184, 40), V3(300, 184, 40), "leg").find("within 5.0 m of no-fly zone nfz-c"),
            std::string::npos);
  EXPECT_EQ(gate.check_leg(V3(280, 60, 70), V3(360, 60, 70), "leg"), "") << "over the square zone";
  // A concave geofence: a leg between two inside points that cuts the notch leaves it.
  Airspace notched = test::test_airspace();
  notched.geofence = {{0, 0}, {400, 0}, {400, 300}, {200, 300}, {200, 150}, {150, 150}, {150, 300}, {0, 300}};
  notched.no_fly_zones.clear();
  const SafetyGate g2(notched, GateConfig{}, EnergyModel{}, V3(20, 20, 0));
  EXPECT_NE(g2.check_leg(V3(100, 250, 40), V3(300, 250, 40), "leg 3").find("leg 3 from (100.0, 250.0, 40.0)"),
            std::string::npos);
  EXPECT_NE(g2.check_leg(V3(100, 250, 40), V3(300, 250, 40), "leg").find("leaves the geofence"), std::string::npos);
  EXPECT_EQ(g2.check_leg(V3(100, 100, 40), V3(300, 100, 40), "leg"), "");
}

TEST(SafetyGate, ALegFromInsideAZonesMarginMayOnlyMoveAway) {
  const SafetyGate gate = test_gate();
  const V3 near(200, 182, 40);  // 2 m outside the cylinder, inside the 5 m margin
  EXPECT_EQ(gate.check_leg(near, V3(200, 250, 40), "leg"), "") << "straight away";
  EXPECT_EQ(gate.check_leg(near, V3(260, 230, 40), "leg"), "") << "away at an angle";
  EXPECT_NE(gate.check_leg(near, V3(120, 150, 40), "leg"), "") << "around and into it";
  EXPECT_NE(gate.check_leg(near, V3(200, 184, 40), "leg"), "") << "ending still within the margin";
  const V3 inside(200, 170, 40);  // 10 m inside (an intrusion): only out
  EXPECT_EQ(gate.check_leg(inside, V3(200, 260, 40), "leg"), "");
  EXPECT_NE(gate.check_leg(inside, V3(200, 100, 40), "leg"), "") << "across the zone";
}

TEST(SafetyGate, BatteryReserveToReturnAndSpeed) {
  const SafetyGate gate = test_gate();
  const BatteryEstimate e = gate.estimate_battery(V3(20, 20, 40), {V3(380, 20, 40)}, 5.0, 50.0);
  const EnergyModel m;
  EXPECT_NEAR(e.route_pct, m.margin_factor * (360.0 * m.percent_per_m(5.0) + m.settle_s_per_waypoint * m.percent_per_s()),
              1e-9);
  EXPECT_NEAR(e.return_pct, m.margin_factor * (360.0 * m.percent_per_m(5.0) + 40.0 / 1.0 * m.percent_per_s()), 1e-9);
  EXPECT_NEAR(e.left_pct, 50.0 - e.route_pct - e.return_pct, 1e-12);
  EXPECT_EQ(gate.check_battery(V3(20, 20, 40), {V3(380, 20, 40)}, 5.0, 50.0), "");
  const std::string low = gate.check_battery(V3(20, 20, 40), {V3(380, 20, 40)}, 5.0, 40.0);
  EXPECT_NE(low.find("battery reserve: 40.0 % now"), std::string::npos) << low;
  EXPECT_EQ(gate.check_speed(12.0), "");
  EXPECT_NE(gate.check_speed(12.5).find("above the vehicle's maximum 12.0 m/s"), std::string::npos);
  EXPECT_NE(gate.check_route(V3(20, 20, 40), {V3(380, 20, 40)}, 13.0, 90.0).find("speed"), std::string::npos);
  EXPECT_NE(gate.check_descent(V3(320, 60, 80)).find("descends through no-fly zone nfz-p"), std::string::npos);
  EXPECT_EQ(gate.check_descent(V3(250, 60, 80)), "");
}

TEST(Maneuvers, OrbitStartsNearestToTheVehicleAndClosesTheLoop) {
  const auto w = orbit_waypoints(V2(0, 0), 50.0, 30.0, V2(100, 0), 20.0);
  ASSERT_EQ(w.size(), 17u) << "2π·50 m in chords ≤ 20 m: 16";
  EXPECT_NEAR((w.front() - V3(50, 0, 30)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((w.back() - w.front()).norm(), 0.0, 1e-9);
  for (std::size_t i = 1; i < w.size(); ++i) {
    EXPECT_NEAR(w[i].head<2>().norm(), 50.0, 1e-9);
    EXPECT_LE((w[i] - w[i - 1]).norm(), 20.0);
  }
  EXPECT_GT(w[1].y(), 0.0) << "counter-clockwise";
  EXPECT_EQ(orbit_waypoints(V2(0, 0), 5.0, 30.0, V2(0, 0), 20.0).size(), 9u) << "at least 8 chords";
}

TEST(Maneuvers, SurveyCoversTheAreaInAlternatingLines) {
  const common::Polygon2d area = {{0, 0}, {100, 0}, {100, 40}, {0, 40}};
  const auto s = survey_waypoints(area, 10.0, 30.0, V2(110, 45), 200);
  EXPECT_EQ(s.lines, 4u);
  ASSERT_EQ(s.waypoints.size(), 8u);
  EXPECT_DOUBLE_EQ(s.line_length_m, 400.0);
  EXPECT_EQ(s.waypoints[0], V3(100, 35, 30)) << "begins at the line end nearest the vehicle";
  EXPECT_EQ(s.waypoints[1], V3(0, 35, 30));
  EXPECT_EQ(s.waypoints[2], V3(0, 25, 30)) << "the next line starts where the last ended";
  EXPECT_EQ(s.waypoints[7], V3(100, 5, 30));
  // Taller than wide: lines run north-south.
  const auto tall = survey_waypoints({{0, 0}, {20, 0}, {20, 100}, {0, 100}}, 10.0, 30.0, V2(0, 0), 200);
  EXPECT_EQ(tall.lines, 2u);
  EXPECT_DOUBLE_EQ(tall.waypoints[0].x(), 5.0);
  EXPECT_DOUBLE_EQ(std::abs(tall.waypoints[1].y() - tall.waypoints[0].y()), 100.0);
  // A triangle: each line spans only the inside.
  const auto tri = survey_waypoints({{0, 0}, {100, 0}, {0, 50}}, 25.0, 30.0, V2(0, 0), 200);
  ASSERT_EQ(tri.lines, 2u);
  EXPECT_NEAR(std::abs(tri.waypoints[1].x() - tri.waypoints[0].x()), 75.0, 1e-9) << "at y = 12.5";
  EXPECT_THROW(survey_waypoints(area, 0.1, 30.0, V2(0, 0), 200), std::invalid_argument);
  EXPECT_THROW(survey_waypoints({{0, 0}, {1, 1}, {2, 2}}, 10.0, 30.0, V2(0, 0), 200), std::invalid_argument);
}

TEST(PathPlanner, GoesAroundACylinderAndAPolygonAndPassesTheGate) {
  const SafetyGate gate = test_gate();
  std::string why;
  const auto plan = plan_path(gate, V3(100, 150, 40), V2(300, 150), 40.0, PlannerConfig{}, &why);
  ASSERT_TRUE(plan.has_value()) << why;
  EXPECT_EQ(plan->avoided, std::vector<std::string>{"nfz-c"});
  EXPECT_EQ(gate.check_path(V3(100, 150, 40), plan->waypoints), "");
  EXPECT_EQ(plan->waypoints.back(), V3(300, 150, 40));
  EXPECT_GT(plan->length_m, 200.0);
  EXPECT_LT(plan->length_m, 200.0 + 2 * 40.0) << "a short way round, not a wide loop";
  // Below the square zone's ceiling its corners are used; above, it is flown over.
  const auto around = plan_path(gate, V3(250, 60, 40), V2(380, 60), 40.0, PlannerConfig{}, &why);
  ASSERT_TRUE(around.has_value()) << why;
  EXPECT_EQ(around->avoided, std::vector<std::string>{"nfz-p"});
  EXPECT_EQ(gate.check_path(V3(250, 60, 40), around->waypoints), "");
  const auto over = plan_path(gate, V3(250, 60, 40), V2(380, 60), 80.0, PlannerConfig{}, &why);
  ASSERT_TRUE(over.has_value()) << why;
  EXPECT_TRUE(over->avoided.empty());
  EXPECT_EQ(over->waypoints.size(), 2u) << "climb, then straight";
  EXPECT_EQ(over->waypoints[0], V3(250, 60, 80));
}

TEST(PathPlanner, SaysWhyWhenThereIsNoRoute) {
  const SafetyGate gate = test_gate();
  std::string why;
  EXPECT_FALSE(plan_path(gate, V3(100, 150, 40), V2(200, 150), 40.0, PlannerConfig{}, &why).has_value());
  EXPECT_NE(why.find("inside no-fly zone nfz-c"), std::string::npos) << why;
  Airspace walled = test::test_airspace();
  NoFlyZone wall;
  wall.id = "wall";
  wall.polygon = {{180, -50}, {220, -50}, {220, 350}, {180, 350}};  // across the whole geofence
  walled.no_fly_zones = {wall};
  const SafetyGate g2(walled, GateConfig{}, EnergyModel{}, V3(20, 20, 0));
  EXPECT_FALSE(plan_path(g2, V3(100, 150, 40), V2(300, 150), 40.0, PlannerConfig{}, &why).has_value());
  EXPECT_NE(why.find("no route from"), std::string::npos) << why;
}

a3lcm::fc_status_t status(int32_t seq, bool accepted, int8_t mode, const V3& p,
                          int8_t failsafe = a3lcm::fc_status_t::FAILSAFE_NONE) {
  a3lcm::fc_status_t s{};
  s.last_command_seq = seq;
  s.last_command_accepted = accepted;
  s.last_command_reason = accepted ? "" : "outside the geofence";
  s.mode = mode;
  s.failsafe = failsafe;
  for (int k = 0; k < 3; ++k) s.p_W_m[k] = p[k];
  return s;
}

TEST(OnboardRoute, DecidesFromTheFcsStatus) {
  using E = OnboardRoute::Event;
  constexpr int8_t kHold = a3lcm::fc_status_t::HOLD, kGoto = a3lcm::fc_status_t::GOTO;
  OnboardRoute r("navigate_to", {RoutePoint{V3(10, 0, 30)}, RoutePoint{V3(20, 0, 30)}}, 5.0, RouteEnd::kHold);
  r.leg_sent(7);
  EXPECT_EQ(r.on_status(status(6, true, kHold, V3(0, 0, 30)), 2.0).event, E::kNone) << "stale: about an older command";
  EXPECT_EQ(r.on_status(status(7, true, kGoto, V3(5, 0, 30)), 2.0).event, E::kNone);
  EXPECT_EQ(r.on_status(status(7, true, kHold, V3(9, 0, 30)), 2.0).event, E::kArrived);
  const auto short_hold = r.on_status(status(7, true, kHold, V3(4, 0, 30), a3lcm::fc_status_t::FAILSAFE_LINK_LOSS), 2.0);
  EXPECT_EQ(short_hold.event, E::kAborted);
  EXPECT_NE(short_hold.reason.find("6.0 m short of waypoint 1 (failsafe link_loss)"), std::string::npos)
      << short_hold.reason;
  const auto refused = r.on_status(status(7, false, kHold, V3(0, 0, 30)), 2.0);
  EXPECT_EQ(refused.event, E::kAborted);
  EXPECT_NE(refused.reason.find("refused leg 1 of 2: outside the geofence"), std::string::npos);
  EXPECT_EQ(r.on_status(status(7, true, a3lcm::fc_status_t::RETURN_HOME, V3(5, 0, 30)), 2.0).event, E::kAborted);
  EXPECT_EQ(r.on_status(status(8, true, kGoto, V3(5, 0, 30)), 2.0).event, E::kAborted) << "somebody else commanded";
  r.compatible_command_sent(8);
  EXPECT_EQ(r.on_status(status(8, false, kGoto, V3(5, 0, 30)), 2.0).event, E::kNone) << "a refused SET_SPEED";
  EXPECT_EQ(r.on_status(status(8, true, kHold, V3(10, 0, 30)), 2.0).event, E::kArrived);
  EXPECT_TRUE(r.advance());
  EXPECT_EQ(r.remaining(), std::vector<V3>{V3(20, 0, 30)});
  r.leg_sent(9);
  EXPECT_EQ(r.on_status(status(8, true, kHold, V3(10, 0, 30)), 2.0).event, E::kNone) << "the old leg's status";
  EXPECT_FALSE(r.advance());
  EXPECT_THROW(OnboardRoute("x", {}, 5.0, RouteEnd::kHold), std::invalid_argument);
}

TEST(Swarm, ClosestApproachIsExactBetweenPiecewiseLinearPlans) {
  TrafficPlan a, b;
  a.path = {{0.0, V3(0, 0, 40)}, {20.0, V3(200, 0, 40)}};
  b.path = {{0.0, V3(100, 100, 40)}, {20.0, V3(100, -100, 40)}};
  const Approach c = closest_approach(a, b, 0.0, 60.0);
  EXPECT_NEAR(c.distance_m, 0.0, 1e-9) << "they cross at (100, 0) at t = 10 s";
  EXPECT_NEAR(c.t_s, 10.0, 1e-9);
  // Against brute-force sampling on a bent path.
  b.path = {{0.0, V3(50, 80, 60)}, {7.0, V3(120, 30, 45)}, {30.0, V3(150, 90, 40)}};
  const Approach exact = closest_approach(a, b, 2.0, 40.0);
  double sampled = 1e9;
  for (double t = 2.0; t <= 42.0; t += 0.001) sampled = std::min(sampled, (a.position_at(t) - b.position_at(t)).norm());
  EXPECT_NEAR(exact.distance_m, sampled, 1e-3);
  EXPECT_LE(exact.distance_m, sampled + 1e-9);
}

TEST(Swarm, AClimbedPlanRampsUpFromWhenItWasAsked) {
  TrafficPlan p;
  p.path = {{0.0, V3(0, 0, 40)}, {100.0, V3(500, 0, 40)}};
  const TrafficPlan c = climbed_plan(p, 20.0, 40.0, 2.5);
  EXPECT_EQ(c.position_at(10.0), p.position_at(10.0)) << "unchanged before";
  EXPECT_NEAR(c.position_at(28.0).z(), 60.0, 1e-9);
  EXPECT_NEAR(c.position_at(50.0).z(), 80.0, 1e-9);
  EXPECT_NEAR(c.position_at(50.0).x(), 250.0, 1e-9) << "keeps its course";
  EXPECT_NEAR(c.position_at(200.0).z(), 80.0, 1e-9);
}

TEST(Sensors, ReadFromTheScenarioWithKindsAndHealth) {
  const auto c = test::test_config();
  SensorSuite s(c.sensors, ImageSizes{});
  EXPECT_TRUE(s.active("rgb")) << "rgb is on from the start";
  EXPECT_FALSE(s.active("thermal"));
  EXPECT_FALSE(s.find("lidar")->usable);
  EXPECT_FALSE(s.find("gnss")->imaging);
  EXPECT_EQ(s.find("main_camera")->kind, "rgb");
  EXPECT_TRUE(s.find("main_camera")->payload);
  EXPECT_FALSE(s.find("drop_box")->imaging);
  EXPECT_EQ(s.image_bytes(*s.find("thermal")), 650'000);
  EXPECT_EQ(s.image_bytes(*s.find("lidar")), 6'000'000);
  SensorSuite none(SensorSuiteConfig{}, ImageSizes{});
  ASSERT_NE(none.find("rgb"), nullptr) << "rgb when the scenario lists nothing";
  SensorSuite radar(SensorSuiteConfig{{{"radar", "ok"}}, {}}, ImageSizes{});
  EXPECT_EQ(radar.image_bytes(*radar.find("radar")), 2'000'000) << "other sensors: the default size";
  try {
    SensorSuite bad(SensorSuiteConfig{{}, {{"", "camera", "", 0.0}}}, ImageSizes{});
    ADD_FAILURE() << "a payload without an id";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "uav.payloads[0].id: expected a non-empty string");
  }
}

TEST(Weather, ReadFromEnvWithErrorsNamingTheField) {
  const WeatherService w(WeatherEnv{"dust", 7.5, 240.0, std::nullopt}, WeatherConfig{});
  EXPECT_EQ(w.weather(), "dust");
  EXPECT_DOUBLE_EQ(w.gust_mps(), 10.5);
  EXPECT_EQ(w.weather_update(SelfView{}).payload["advisory"], "caution");
  try {
    WeatherService bad(WeatherEnv{"clear", -1.0, 0.0, std::nullopt}, WeatherConfig{});
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "env.wind_mps: expected a finite number >= 0");
  }
}

}  // namespace
}  // namespace a3::vehicle
