// The tool server's motion tools in virtual time against the fake flight controller: each
// tool's happy path and the fc commands it makes, the safety gate refusing unsafe motion with
// a reason while nothing reaches A3_FC_CMD, argument errors, fc refusals and silence, onboard
// routes (navigate_to, orbit, survey with captures, detoured return), and a new motion
// command or an fc failsafe ending a route.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/vehicle/vehicle_test_util.hpp"

namespace a3::vehicle {
namespace {

using test::mcp;
using test::Rig;

Eigen::Vector3d target_of(const a3lcm::fc_command_t& c) {
  return Eigen::Vector3d(c.target_W_m[0], c.target_W_m[1], c.target_W_m[2]);
}

TEST(ToolServerMotion, TakeoffSendsTakeoffAndAnswersWithTheFcsStatus) {
  Rig rig;
  const auto obs = rig.call(mcp("takeoff", {{"altitude_m", 30.0}}));
  EXPECT_EQ(obs["tool"], "takeoff");
  const auto& r = obs["result"];
  EXPECT_EQ(r["status"], "accepted") << obs.dump();
  EXPECT_EQ(r["mode"], "takeoff");
  EXPECT_DOUBLE_EQ(r["target_altitude_m"].get<double>(), 30.0);
  EXPECT_NEAR(r["eta_s"].get<double>(), 15.0, 1e-9) << "30 m at the 2 m/s climb speed";
  EXPECT_NEAR(r["pose"]["x"].get<double>(), 20.0, 1e-9);
  ASSERT_EQ(rig.fc.commands.size(), 1u);
  EXPECT_EQ(rig.fc.commands[0].command, int8_t{a3lcm::fc_command_t::TAKEOFF});
  EXPECT_EQ(rig.fc.commands[0].seq, 1);
  EXPECT_DOUBLE_EQ(rig.fc.commands[0].target_W_m[2], 30.0);
  rig.run_for(20.0);
  EXPECT_NEAR(rig.fc.position().z(), 30.0, 1e-6);
  EXPECT_EQ(rig.server.counters().get("fc_commands"), 1u);
}

TEST(ToolServerMotion, SetWaypointFliesThereAndTheRouteCompletes) {
  Rig rig;
  rig.take_off();
  const auto r = rig.result(mcp("set_waypoint", {{"x", 100.0}, {"y", 60.0}, {"z", 50.0}, {"speed_mps", 8.0}}));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  EXPECT_EQ(r["mode"], "goto");
  EXPECT_DOUBLE_EQ(r["target"]["x"].get<double>(), 100.0);
  EXPECT_DOUBLE_EQ(r["speed_mps"].get<double>(), 8.0);
  const double horizontal = std::hypot(80.0, 40.0);
  EXPECT_NEAR(r["distance_m"].get<double>(), std::hypot(horizontal, 10.0), 0.05);
  EXPECT_NEAR(r["eta_s"].get<double>(), horizontal / 8.0 + 10.0 / 2.0, 0.05);
  const auto& goto_cmd = rig.fc.commands.back();
  EXPECT_EQ(goto_cmd.command, int8_t{a3lcm::fc_command_t::GOTO});
  EXPECT_EQ(goto_cmd.seq, 2);
  EXPECT_DOUBLE_EQ(goto_cmd.speed_limit_mps, 8.0);
  rig.run_for(20.0);
  EXPECT_LT((rig.fc.position() - Eigen::Vector3d(100, 60, 50)).norm(), 1e-6);
  EXPECT_EQ(rig.server.counters().get("routes_completed"), 1u);
  EXPECT_EQ(rig.server.route(), nullptr);
}

TEST(ToolServerMotion, SetAltitudeKeepsTheHorizontalPosition) {
  Rig rig;
  rig.take_off(30.0);
  const auto r = rig.result(mcp("set_altitude", {{"z", 70.0}}));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  const Eigen::Vector3d t = target_of(rig.fc.commands.back());
  EXPECT_NEAR(t.x(), 20.0, 1e-9);
  EXPECT_NEAR(t.y(), 20.0, 1e-9);
  EXPECT_DOUBLE_EQ(t.z(), 70.0);
}

TEST(ToolServerMotion, TheGateRefusesUnsafeWaypointsWithAReasonAndNothingReachesTheFc) {
  Rig rig;
  rig.take_off();
  const std::size_t commands_before = rig.fc.commands.size();
  struct Case {
    double x, y, z;
    std::string reason;
  };
  const Case cases[] = {
      {500, 100, 40, "is outside the geofence"},
      {398, 100, 40, "2.0 m from the geofence edge, closer than the 5.0 m margin"},
      {100, 100, 150, "altitude 150.0 m is above the envelope's maximum 120.0 m"},
      {100, 100, 5, "altitude 5.0 m is below the envelope's minimum 10.0 m"},
      {200, 150, 40, "is inside no-fly zone nfz-c"},
      {200, 183, 40, "from no-fly zone nfz-c, closer than the 5.0 m margin"},
      {380, 280, 40, "passes through or within 5.0 m of no-fly zone nfz-c"},
  };
  for (const auto& c : cases) {
    const auto obs = rig.call(mcp("set_waypoint", {{"x", c.x}, {"y", c.y}, {"z", c.z}}));
    const auto& r = obs["result"];
    EXPECT_EQ(r["status"], "refused") << obs.dump();
    EXPECT_EQ(r["by"], "safety_gate");
    EXPECT_NE(r["reason"].get<std::string>().find(c.reason), std::string::npos) << r["reason"];
    EXPECT_TRUE(r["pose"].is_object());
  }
  EXPECT_EQ(rig.fc.commands.size(), commands_before);
  EXPECT_EQ(rig.server.counters().get("gate_refusals"), std::size(cases));
  ASSERT_EQ(rig.probe.safety.size(), std::size(cases));
  EXPECT_EQ(rig.probe.safety[0].kind, "gate_refusal");
  EXPECT_EQ(rig.probe.safety[0].source, "tool_server");
  EXPECT_NE(rig.probe.safety[0].detail.find("set_waypoint: "), std::string::npos);
}

TEST(ToolServerMotion, TheGateKeepsTheBatteryReserveToReturn) {
  Rig rig;
  rig.take_off();
  rig.fc.set_battery(40.0);
  rig.run_for(0.2);
  // 360 m out at 5 m/s plus the way back and the descent: about 21 % of the battery.
  const auto far = rig.result(mcp("set_waypoint", {{"x", 380.0}, {"y", 20.0}, {"z", 40.0}}));
  EXPECT_EQ(far["status"], "refused") << far.dump();
  const std::string reason = far["reason"];
  EXPECT_NE(reason.find("battery reserve: 40.0 % now"), std::string::npos) << reason;
  EXPECT_NE(reason.find("below the 25.0 % reserve"), std::string::npos) << reason;
  const BatteryEstimate e = rig.server.gate().estimate_battery(Eigen::Vector3d(20, 20, 40), {{380, 20, 40}}, 5.0, 40.0);
  EXPECT_GT(e.route_pct, 7.0);
  EXPECT_LT(e.left_pct, 25.0);
  const auto near = rig.result(mcp("set_waypoint", {{"x", 60.0}, {"y", 40.0}, {"z", 40.0}}));
  EXPECT_EQ(near["status"], "accepted") << near.dump();
}

TEST(ToolServerMotion, SpeedsAboveTheVehiclesLimitAreRefused) {
  Rig rig;
  rig.take_off();
  const std::size_t before = rig.fc.commands.size();
  const auto r = rig.result(mcp("set_waypoint", {{"x", 60.0}, {"y", 40.0}, {"z", 40.0}, {"speed_mps", 20.0}}));
  EXPECT_EQ(r["status"], "refused");
  EXPECT_NE(r["reason"].get<std::string>().find("speed 20.0 m/s is above the vehicle's maximum 12.0 m/s"),
            std::string::npos);
  const auto s = rig.result(mcp("adjust_speed", {{"speed_mps", 13.0}}));
  EXPECT_EQ(s["status"], "refused");
  EXPECT_EQ(rig.fc.commands.size(), before);
}

TEST(ToolServerMotion, BadCallsGetErrorObservationsNamingTheProblemAndNeverReachTheFc) {
  Rig rig;
  rig.take_off();
  const std::size_t before = rig.fc.commands.size();
  struct Case {
    nlohmann::json action;
    std::string expected_tool, needle;
  };
  const Case cases[] = {
      {mcp("fly_somewhere", {{"x", 1}}), "fly_somewhere", "unknown tool 'fly_somewhere'"},
      {mcp("set_waypoint", {{"x", 1.0}, {"y", 2.0}}), "set_waypoint", "'z'"},
      {mcp("set_waypoint", {{"x", "ten"}, {"y", 2.0}, {"z", 30.0}}), "set_waypoint", "args/x"},
      {mcp("set_waypoint", {{"x", 1.0}, {"y", 2.0}, {"z", 30.0}, {"colour", "red"}}), "set_waypoint", "colour"},
      {mcp("takeoff", {{"altitude_m", 0.0}}), "takeoff", "args/altitude_m"},
      {mcp("navigate_to", {{"waypoints", {{1.0, 2.0}}}}), "navigate_to", "args/waypoints/0"},
      {mcp("execute_maneuver", {{"maneuver", "orbit"}, {"radius_m", 20.0}}), "execute_maneuver", "args/center"},
      {mcp("execute_maneuver", {{"maneuver", "loop"}}), "execute_maneuver", "args/maneuver"},
      {mcp("execute_maneuver", {{"maneuver", "survey"}, {"area", {{0, 0}, {10, 0}, {20, 0}}}}), "execute_maneuver",
       "args/area"},
      {mcp("adjust_speed", {{"speed_mps", -1.0}}), "adjust_speed", "args/speed_mps"},
      {{{"type", "mcp"}, {"args", nlohmann::json::object()}}, "", "action/name"},
  };
  for (const auto& c : cases) {
    const auto obs = rig.call(c.action);
    EXPECT_EQ(obs["tool"], c.expected_tool) << obs.dump();
    EXPECT_EQ(obs["result"]["status"], "error") << obs.dump();
    EXPECT_NE(obs["result"]["error"].get<std::string>().find(c.needle), std::string::npos)
        << c.action.dump() << " -> " << obs.dump();
  }
  EXPECT_EQ(rig.fc.commands.size(), before);
  EXPECT_EQ(rig.server.counters().get("errors"), std::size(cases));
}

TEST(ToolServerMotion, AnFcRefusalIsPassedOnWithItsReason) {
  Rig rig;  // on the ground, disarmed
  const auto r = rig.result(mcp("set_waypoint", {{"x", 60.0}, {"y", 40.0}, {"z", 40.0}}));
  EXPECT_EQ(r["status"], "refused") << r.dump();
  EXPECT_EQ(r["by"], "flight_controller");
  EXPECT_EQ(r["reason"], "not armed");
  EXPECT_EQ(r["mode"], "disarmed");
  EXPECT_EQ(rig.server.counters().get("fc_refusals"), 1u);
  EXPECT_EQ(rig.server.route(), nullptr) << "a refused first leg ends the route";
}

TEST(ToolServerMotion, NoStatusInTimeGivesATimeoutObservation) {
  test::FakeFcConfig dead;
  dead.answer_commands = false;
  Rig rig(test::test_config(), dead);
  // Without any status the gate has no position: motion is refused outright.
  const auto refused = rig.result(mcp("takeoff", {{"altitude_m", 30.0}}));
  EXPECT_EQ(refused["status"], "refused");
  EXPECT_NE(refused["reason"].get<std::string>().find("no telemetry"), std::string::npos);
  // hold needs no position: it is sent, and nothing answers.
  const double sent_at = rig.now_s();
  const auto obs = rig.call(mcp("hold"), 5.0);
  EXPECT_EQ(obs["result"]["status"], "timeout") << obs.dump();
  EXPECT_NE(obs["result"]["reason"].get<std::string>().find("within 2.0 s"), std::string::npos);
  EXPECT_NEAR(rig.probe.down.back().t_s - sent_at, 2.0, 0.02);
  EXPECT_EQ(rig.server.counters().get("timeouts"), 1u);
}

TEST(ToolServerMotion, NavigateToIsAnOnboardRouteFlownLegByLeg) {
  Rig rig;
  rig.take_off();
  const std::size_t before = rig.fc.commands.size();
  const auto r = rig.result(mcp("navigate_to", {{"waypoints", {{60, 20, 40}, {60, 80, 50}, {100, 80, 50}}}}));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  EXPECT_EQ(r["waypoints"], 3);
  EXPECT_NEAR(r["route_length_m"].get<double>(), 40.0 + std::hypot(60.0, 10.0) + 40.0, 0.05);
  EXPECT_EQ(rig.fc.commands.size(), before + 1) << "answered after the first leg, before the others";
  ASSERT_NE(rig.server.route(), nullptr);
  rig.run_for(60.0);
  ASSERT_EQ(rig.fc.commands.size(), before + 3);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& c = rig.fc.commands[before + i];
    EXPECT_EQ(c.command, int8_t{a3lcm::fc_command_t::GOTO});
    EXPECT_EQ(c.seq, static_cast<int32_t>(before + i + 1));
  }
  EXPECT_EQ(target_of(rig.fc.commands[before + 1]), Eigen::Vector3d(60, 80, 50));
  EXPECT_LT((rig.fc.position() - Eigen::Vector3d(100, 80, 50)).norm(), 1e-6);
  EXPECT_EQ(rig.server.counters().get("routes_completed"), 1u);
}

TEST(ToolServerMotion, TheGateChecksEveryLegOfARoute) {
  Rig rig;
  rig.take_off();
  const std::size_t before = rig.fc.commands.size();
  const auto r = rig.result(mcp("navigate_to", {{"waypoints", {{100, 150, 40}, {300, 150, 40}, {350, 250, 40}}}}));
  EXPECT_EQ(r["status"], "refused");
  EXPECT_NE(r["reason"].get<std::string>().find("leg 2 from (100.0, 150.0, 40.0) to (300.0, 150.0, 40.0)"),
            std::string::npos)
      << r["reason"];
  EXPECT_EQ(rig.fc.commands.size(), before);
}

TEST(ToolServerMotion, ANewMotionCommandCancelsARunningRoute) {
  Rig rig;
  rig.take_off();
  rig.result(mcp("navigate_to", {{"waypoints", {{150, 20, 40}, {150, 100, 40}, {20, 100, 40}}}}));
  rig.run_for(5.0);
  ASSERT_NE(rig.server.route(), nullptr);
  const auto r = rig.result(mcp("hold"));
  EXPECT_EQ(r["status"], "accepted");
  EXPECT_EQ(r["mode"], "hold");
  EXPECT_EQ(rig.server.route(), nullptr);
  const std::size_t after_hold = rig.fc.commands.size();
  rig.run_for(60.0);
  EXPECT_EQ(rig.fc.commands.size(), after_hold) << "no further legs";
  EXPECT_EQ(rig.server.counters().get("routes_aborted"), 1u);
  EXPECT_EQ(rig.server.counters().get("routes_completed"), 0u);
}

TEST(ToolServerMotion, AnFcFailsafeEndsTheRoute) {
  Rig rig;
  rig.take_off();
  rig.result(mcp("navigate_to", {{"waypoints", {{150, 20, 40}, {150, 100, 40}}}}));
  rig.run_for(3.0);
  rig.fc.force_mode(a3lcm::fc_status_t::RETURN_HOME, a3lcm::fc_status_t::FAILSAFE_LOW_BATTERY);
  rig.run_for(0.2);
  EXPECT_EQ(rig.server.route(), nullptr);
  EXPECT_EQ(rig.server.counters().get("routes_aborted"), 1u);
  const std::size_t n = rig.fc.commands.size();
  rig.run_for(60.0);
  EXPECT_EQ(rig.fc.commands.size(), n);
}

TEST(ToolServerMotion, AdjustSpeedDuringARouteKeepsItAndLaterLegsUseTheNewSpeed) {
  Rig rig;
  rig.take_off();
  rig.result(mcp("navigate_to", {{"waypoints", {{60, 20, 40}, {60, 80, 40}}}}));
  rig.run_for(2.0);
  const auto r = rig.result(mcp("adjust_speed", {{"speed_mps", 9.0}}));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  EXPECT_DOUBLE_EQ(r["speed_mps"].get<double>(), 9.0);
  ASSERT_NE(rig.server.route(), nullptr) << "adjust_speed does not cancel the route";
  EXPECT_EQ(rig.fc.commands.back().command, int8_t{a3lcm::fc_command_t::SET_SPEED});
  rig.run_for(30.0);
  EXPECT_EQ(rig.server.counters().get("routes_completed"), 1u);
  EXPECT_EQ(rig.fc.commands.back().command, int8_t{a3lcm::fc_command_t::GOTO});
  EXPECT_DOUBLE_EQ(rig.fc.commands.back().speed_limit_mps, 9.0);
  EXPECT_LT((rig.fc.position() - Eigen::Vector3d(60, 80, 40)).norm(), 1e-6);
}

TEST(ToolServerMotion, OrbitFliesAFullCircleAroundTheCentre) {
  Rig rig;
  rig.take_off();
  const auto r = rig.result(mcp("execute_maneuver", {{"maneuver", "orbit"}, {"center", {80, 80}}, {"radius_m", 25.0}}));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  const int n = r["waypoints"].get<int>();
  EXPECT_EQ(n, 9) << "2π·25 m in chords of at most 20 m: 8 chords, 9 points";
  rig.run_for(120.0);
  EXPECT_EQ(rig.server.counters().get("routes_completed"), 1u);
  int gotos = 0;
  for (const auto& c : rig.fc.commands) {
    if (c.command != a3lcm::fc_command_t::GOTO) continue;
    ++gotos;
    EXPECT_NEAR((target_of(c).head<2>() - Eigen::Vector2d(80, 80)).norm(), 25.0, 1e-9);
    EXPECT_DOUBLE_EQ(c.target_W_m[2], 40.0);
  }
  EXPECT_EQ(gotos, n);
}

TEST(ToolServerMotion, SurveyFliesTheLawnmowerAndCapturesAtEveryLineEnd) {
  Rig rig;
  rig.take_off();
  const auto r = rig.result(mcp("execute_maneuver", {{"maneuver", "survey"},
                                                     {"area", {{50, 50}, {150, 50}, {150, 100}, {50, 100}}},
                                                     {"spacing_m", 25.0},
                                                     {"z", 45.0},
                                                     {"capture", true}}));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  EXPECT_EQ(r["lines"], 2);
  EXPECT_EQ(r["waypoints"], 4);
  EXPECT_EQ(r["captures"], 4);
  rig.run_for(120.0);
  EXPECT_EQ(rig.server.counters().get("routes_completed"), 1u);
  ASSERT_EQ(rig.probe.payload.size(), 4u);
  ASSERT_EQ(rig.server.images().records().size(), 4u);
  const Eigen::Vector3d offset = test::FakeFcConfig{}.true_offset_W_m;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& e = rig.probe.payload[i];
    EXPECT_EQ(e.kind, "capture");
    EXPECT_EQ(e.sensor, "rgb");
    EXPECT_EQ(e.size_bytes, 3'500'000);
    EXPECT_FALSE(e.downlinked) << "survey images stay on board";
    const Eigen::Vector3d p(e.p_W_m[0], e.p_W_m[1], e.p_W_m[2]);
    const Eigen::Vector3d wp = rig.server.images().records()[i].p_W_m - offset;
    EXPECT_NEAR(p.z(), 45.0, 1e-6);
    EXPECT_TRUE(std::abs(wp.y() - 62.5) < 1e-6 || std::abs(wp.y() - 87.5) < 1e-6) << wp.transpose();
    EXPECT_TRUE(std::abs(wp.x() - 50.0) < 1e-6 || std::abs(wp.x() - 150.0) < 1e-6) << wp.transpose();
  }
  EXPECT_EQ(rig.server.counters().get("image_bytes_downlinked"), 0u);
}

TEST(ToolServerMotion, YawTurnsInPlace) {
  Rig rig;
  rig.take_off();
  const auto r = rig.result(mcp("execute_maneuver", {{"maneuver", "yaw"}, {"heading_deg", 180.0}}));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  const auto& c = rig.fc.commands.back();
  EXPECT_EQ(c.command, int8_t{a3lcm::fc_command_t::GOTO});
  EXPECT_DOUBLE_EQ(c.yaw_deg, 180.0);
  EXPECT_NEAR(c.target_W_m[0], 20.0, 1e-9);
  EXPECT_NEAR(c.target_W_m[2], 40.0, 1e-9);
}

TEST(ToolServerMotion, LandAndItsDescentCheck) {
  Rig rig;
  rig.take_off();
  // Above the square zone (ceiling 60 m, 5 m margin): flying over at 80 m is allowed...
  rig.fly_to(Eigen::Vector3d(250, 60, 80));
  rig.fly_to(Eigen::Vector3d(320, 60, 80));
  const std::size_t before = rig.fc.commands.size();
  // ...landing through it is not.
  const auto refused = rig.result(mcp("land"));
  EXPECT_EQ(refused["status"], "refused");
  EXPECT_NE(refused["reason"].get<std::string>().find("descends through no-fly zone nfz-p"), std::string::npos);
  EXPECT_EQ(rig.fc.commands.size(), before);
  rig.fly_to(Eigen::Vector3d(250, 60, 80));
  const auto r = rig.result(mcp("land"));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  EXPECT_EQ(r["mode"], "land");
  EXPECT_NEAR(r["eta_s"].get<double>(), 80.0, 1e-6);
  EXPECT_EQ(rig.fc.commands.back().command, int8_t{a3lcm::fc_command_t::LAND});
}

TEST(ToolServerMotion, ReturnToHomeIsTheFcsReturnWhenThePathIsClear) {
  Rig rig;
  rig.take_off();
  rig.fly_to(Eigen::Vector3d(100, 60, 40));
  const auto r = rig.result(mcp("return_to_home"));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  EXPECT_EQ(r["route"], "direct");
  EXPECT_EQ(r["mode"], "return_home");
  EXPECT_NEAR(r["distance_m"].get<double>(), std::hypot(80.0, 40.0), 0.05);
  EXPECT_EQ(rig.fc.commands.back().command, int8_t{a3lcm::fc_command_t::RETURN_HOME});
}

TEST(ToolServerMotion, ReturnToHomeDetoursAroundANoFlyZoneAndLands) {
  Rig rig;
  rig.take_off();
  rig.fly_to(Eigen::Vector3d(250, 20, 40));
  rig.fly_to(Eigen::Vector3d(250, 200, 40));  // home (20, 20) is behind the cylinder zone
  ASSERT_FALSE(rig.server.gate().check_leg(Eigen::Vector3d(250, 200, 40), Eigen::Vector3d(20, 20, 40), "l").empty());
  const std::size_t before = rig.fc.commands.size();
  const auto r = rig.result(mcp("return_to_home"));
  EXPECT_EQ(r["status"], "accepted") << r.dump();
  EXPECT_EQ(r["route"], "detour");
  EXPECT_EQ(r["avoids"], nlohmann::json::array({"nfz-c"}));
  rig.run_for(200.0);
  EXPECT_EQ(rig.fc.commands.back().command, int8_t{a3lcm::fc_command_t::LAND});
  EXPECT_LT((rig.fc.position().head<2>() - Eigen::Vector2d(20, 20)).norm(), 1e-6);
  EXPECT_EQ(rig.fc.mode(), int8_t{a3lcm::fc_status_t::DISARMED});
  // Every leg it flew kept clear of the zone.
  Eigen::Vector3d from(250, 200, 40);
  int legs = 0;
  for (std::size_t i = before; i < rig.fc.commands.size(); ++i) {
    const auto& c = rig.fc.commands[i];
    if (c.command != a3lcm::fc_command_t::GOTO) continue;
    ++legs;
    EXPECT_EQ(rig.server.gate().check_leg(from, target_of(c), "leg"), "");
    from = target_of(c);
  }
  EXPECT_GE(legs, 2);
}

TEST(ToolServerMotion, HeartbeatsAreForwardedToTheFcAtOnce) {
  Rig rig;
  a3lcm::link_message_t hb{};
  hb.kind = "heartbeat";
  hb.sender = "agent";
  hb.payload = {'{', '}'};
  hb.payload_length = 2;
  for (int i = 0; i < 3; ++i) {
    rig.send_raw(hb);
    rig.run_for(1.0);
  }
  EXPECT_EQ(rig.fc.heartbeats, 3);
  EXPECT_EQ(rig.server.counters().get("heartbeats_forwarded"), 3u);
  EXPECT_TRUE(rig.fc.commands.empty());
  EXPECT_TRUE(rig.probe.down.empty()) << "heartbeats get no observation";
}

}  // namespace
}  // namespace a3::vehicle
