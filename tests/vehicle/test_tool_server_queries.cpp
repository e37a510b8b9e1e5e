// The tool server's query, sensor and network tools in virtual time: read_telemetry from the
// fc's status and the link's n_t, check_geofence, activate_sensor, capture_image (the image's
// bytes charged to the downlink message, the true position in the payload event),
// switch_network_slice through the slice-switch request/reply; malformed link messages
// dropped and counted; observations in the order of the actions.
#include <gtest/gtest.h>

#include "tests/vehicle/vehicle_test_util.hpp"

namespace a3::vehicle {
namespace {

using test::mcp;
using test::Rig;

void publish_net(Rig& rig, const std::string& slice, double lat_ms, double loss_pct) {
  a3lcm::network_state_t n{};
  n.utime_us = rig.rt.clock().now_us();
  n.slice = slice;
  n.lat_ms = lat_ms;
  n.jitter_ms = 1.25;
  n.loss_pct = loss_pct;
  n.throughput_mbps = 95.5;
  n.edge_load = 0.375;
  rig.rt.bus().publish(common::channels::kNet.of(0), n);
  rig.run_for(0.01);
}

TEST(ToolServerQueries, ReadTelemetryReportsTheFcsEstimateAndTheLink) {
  Rig rig;
  rig.take_off(30.0);
  rig.result(mcp("set_waypoint", {{"x", 60.0}, {"y", 20.0}, {"z", 30.0}}));
  rig.run_for(2.0);
  publish_net(rig, "URLLC", 7.5, 0.0625);
  const auto r = rig.result(mcp("read_telemetry"));
  EXPECT_EQ(r["mode"], "goto");
  EXPECT_EQ(r["armed"], true);
  EXPECT_EQ(r["failsafe"], "none");
  EXPECT_NEAR(r["speed_mps"].get<double>(), 5.0, 1e-9);
  EXPECT_NEAR(r["pose"]["x"].get<double>(), rig.fc.position().x(), 0.3) << "the fc's estimate, at its 10 Hz status";
  EXPECT_NEAR(r["pose"]["z"].get<double>(), 30.0, 1e-9);
  EXPECT_DOUBLE_EQ(r["battery_pct"].get<double>(), 90.0);
  EXPECT_EQ(r["link"]["slice"], "URLLC");
  EXPECT_DOUBLE_EQ(r["link"]["lat_ms"].get<double>(), 7.5);
  EXPECT_DOUBLE_EQ(r["link"]["loss_pct"].get<double>(), 0.063);
  EXPECT_DOUBLE_EQ(r["link"]["throughput_mbps"].get<double>(), 95.5);
  EXPECT_DOUBLE_EQ(r["link"]["edge_load"].get<double>(), 0.375);
  EXPECT_EQ(r["route"]["name"], "set_waypoint");

  const auto picked = rig.result(mcp("read_telemetry", {{"fields", {"battery_pct", "link"}}}));
  EXPECT_EQ(picked.size(), 2u) << picked.dump();
  EXPECT_TRUE(picked.contains("battery_pct"));
  const auto bad = rig.result(mcp("read_telemetry", {{"fields", {"pose", "gps"}}}));
  EXPECT_EQ(bad["status"], "error");
  EXPECT_NE(bad["error"].get<std::string>().find("args/fields/1: unknown field 'gps'"), std::string::npos);
}

TEST(ToolServerQueries, ReadTelemetryBeforeAnyStatusSaysSo) {
  test::FakeFcConfig dead;
  dead.answer_commands = false;
  Rig rig(test::test_config(), dead);
  const auto r = rig.result(mcp("read_telemetry"));
  EXPECT_EQ(r["status"], "error");
  EXPECT_NE(r["error"].get<std::string>().find("no telemetry"), std::string::npos);
}

// The pre-flight check on the ground: the altitude envelope applies once airborne, so the vehicle's
// own position on the ground is judged for a take-off into the envelope there, and says so.
TEST(ToolServerQueries, CheckGeofenceOnTheGroundJudgesTheTakeOffColumn) {
  Rig rig;
  const auto ground = rig.result(mcp("check_geofence"));
  EXPECT_EQ(ground["status"], "inside_geofence") << ground.dump();
  EXPECT_EQ(ground["on_ground"], true);
  EXPECT_EQ(ground["altitude_ok"], true);
  EXPECT_EQ(ground["flyable"], true) << ground.dump();
  EXPECT_NE(ground["note"].get<std::string>().find("at 10.0 m"), std::string::npos) << ground.dump();
  // A point given with its altitude is judged as given, on the ground or not.
  const auto given = rig.result(mcp("check_geofence", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}));
  EXPECT_EQ(given["status"], "outside_altitude_envelope") << given.dump();
  EXPECT_FALSE(given.contains("on_ground"));
}

TEST(ToolServerQueries, CheckGeofenceForAPointAndForTheCurrentPosition) {
  Rig rig;
  rig.take_off(30.0);
  const auto here = rig.result(mcp("check_geofence"));
  EXPECT_EQ(here["status"], "inside_geofence") << here.dump();
  EXPECT_FALSE(here.contains("on_ground")) << "airborne";
  EXPECT_DOUBLE_EQ(here["point"]["z"].get<double>(), 30.0);
  EXPECT_DOUBLE_EQ(here["distance_to_boundary_m"].get<double>(), 20.0);
  EXPECT_EQ(here["flyable"], true);
  EXPECT_EQ(here["nfz_violation"], false);
  EXPECT_EQ(here["nearest_nfz"]["id"], "nfz-c");

  const auto in_zone = rig.result(mcp("check_geofence", {{"x", 210.0}, {"y", 150.0}, {"z", 40.0}}));
  EXPECT_EQ(in_zone["status"], "in_no_fly_zone");
  EXPECT_EQ(in_zone["in_zone"], "nfz-c");
  EXPECT_EQ(in_zone["nfz_violation"], true);
  EXPECT_EQ(in_zone["flyable"], false);

  const auto above_square = rig.result(mcp("check_geofence", {{"x", 320.0}, {"y", 60.0}, {"z", 90.0}}));
  EXPECT_EQ(above_square["status"], "inside_geofence");
  EXPECT_EQ(above_square["nearest_nfz"]["id"], "nfz-p");
  EXPECT_EQ(above_square["nearest_nfz"]["vertical"], "above");

  const auto outside = rig.result(mcp("check_geofence", {{"x", 450.0}, {"y", 100.0}}));
  EXPECT_EQ(outside["status"], "outside_geofence");
  EXPECT_DOUBLE_EQ(outside["distance_to_boundary_m"].get<double>(), -50.0);
  EXPECT_DOUBLE_EQ(outside["point"]["z"].get<double>(), 30.0) << "missing coordinates come from the position";

  const auto low = rig.result(mcp("check_geofence", {{"x", 100.0}, {"y", 100.0}, {"z", 4.0}}));
  EXPECT_EQ(low["status"], "outside_altitude_envelope");
  EXPECT_NE(low["why_not_flyable"].get<std::string>().find("below the envelope's minimum 10.0 m"), std::string::npos);
}

TEST(ToolServerQueries, ActivateSensorSwitchesUsableSensorsAndPayloads) {
  Rig rig;
  const auto thermal = rig.result(mcp("activate_sensor", {{"sensor", "thermal"}}));
  EXPECT_EQ(thermal["status"], "active") << thermal.dump();
  EXPECT_EQ(thermal["was_active"], false);
  ASSERT_EQ(rig.probe.payload.size(), 1u);
  EXPECT_EQ(rig.probe.payload[0].kind, "activated");
  EXPECT_EQ(rig.probe.payload[0].sensor, "thermal");

  const auto camera = rig.result(mcp("activate_sensor", {{"sensor", "main_camera"}}));
  EXPECT_EQ(camera["status"], "active");
  EXPECT_EQ(camera["kind"], "rgb");
  EXPECT_DOUBLE_EQ(camera["power_W"].get<double>(), 15.0);

  const auto off = rig.result(mcp("activate_sensor", {{"sensor", "thermal"}, {"active", false}}));
  EXPECT_EQ(off["status"], "inactive");
  ASSERT_EQ(rig.probe.payload.size(), 3u);
  EXPECT_EQ(rig.probe.payload[2].kind, "deactivated");

  const auto lidar = rig.result(mcp("activate_sensor", {{"sensor", "lidar"}}));
  EXPECT_EQ(lidar["status"], "error");
  EXPECT_EQ(lidar["error"], "args/sensor: lidar is offline and cannot be switched on");
  const auto radar = rig.result(mcp("activate_sensor", {{"sensor", "radar"}}));
  EXPECT_EQ(radar["status"], "error");
  EXPECT_NE(radar["error"].get<std::string>().find("unknown sensor or payload 'radar'"), std::string::npos);
  EXPECT_EQ(rig.probe.payload.size(), 3u);
}

TEST(ToolServerQueries, CaptureImageChargesTheImageToTheDownlinkAndRecordsTheTruePosition) {
  Rig rig;
  rig.take_off(30.0);
  const auto obs = rig.call(mcp("capture_image"));
  const auto& r = obs["result"];
  EXPECT_EQ(r["status"], "captured") << obs.dump();
  EXPECT_EQ(r["image_id"], "img-0001");
  EXPECT_EQ(r["sensor"], "rgb");
  EXPECT_EQ(r["size_bytes"], 3'500'000);
  EXPECT_EQ(r["downlinked"], true);
  const auto& m = rig.probe.down.back().message;
  EXPECT_EQ(m.kind, "image");
  EXPECT_EQ(m.sender, "tool_server");
  EXPECT_EQ(m.payload_size_bytes, 3'500'000 + m.payload_length) << "the image's bytes on top of the JSON";
  ASSERT_EQ(rig.probe.payload.size(), 1u);
  const auto& e = rig.probe.payload[0];
  EXPECT_EQ(e.kind, "capture");
  EXPECT_EQ(e.item_id, "img-0001");
  EXPECT_EQ(e.size_bytes, 3'500'000);
  EXPECT_TRUE(e.downlinked);
  const Eigen::Vector3d truth = rig.fc.position() + test::FakeFcConfig{}.true_offset_W_m;
  EXPECT_NEAR(e.p_W_m[0], truth.x(), 1e-9) << "the true position, not the fc's estimate";
  EXPECT_NEAR(e.p_W_m[1], truth.y(), 1e-9);
  EXPECT_EQ(rig.server.counters().get("image_bytes_downlinked"), 3'500'000u);

  const auto stored = rig.call(mcp("capture_image", {{"store_only", true}}));
  EXPECT_EQ(stored["result"]["downlinked"], false);
  EXPECT_EQ(stored["result"]["stored_on_board"], 1);
  EXPECT_EQ(rig.probe.down.back().message.kind, "observation");
  EXPECT_EQ(rig.probe.down.back().message.payload_size_bytes, rig.probe.down.back().message.payload_length);
}

TEST(ToolServerQueries, CaptureNeedsAnActiveImagingSensorAndSizesBySensor) {
  Rig rig;
  const auto inactive = rig.result(mcp("capture_image", {{"sensor", "thermal"}}));
  EXPECT_EQ(inactive["status"], "error");
  EXPECT_NE(inactive["error"].get<std::string>().find("thermal is not active"), std::string::npos);
  const auto gnss = rig.result(mcp("capture_image", {{"sensor", "gnss"}}));
  EXPECT_EQ(gnss["error"], "args/sensor: gnss does not take images");
  const auto lidar = rig.result(mcp("capture_image", {{"sensor", "lidar"}}));
  EXPECT_EQ(lidar["error"], "args/sensor: lidar is offline");
  rig.result(mcp("activate_sensor", {{"sensor", "thermal"}}));
  const auto thermal = rig.call(mcp("capture_image", {{"sensor", "thermal"}}));
  EXPECT_EQ(thermal["result"]["size_bytes"], 650'000);
  EXPECT_EQ(rig.probe.down.back().message.payload_size_bytes, 650'000 + rig.probe.down.back().message.payload_length);
}

TEST(ToolServerQueries, SwitchNetworkSliceGoesThroughTheLinkEmulatorsReply) {
  Rig rig;
  const auto r = rig.result(mcp("switch_network_slice", {{"slice", "URLLC"}}));
  EXPECT_EQ(r["status"], "switching") << r.dump();
  EXPECT_EQ(r["slice"], "URLLC");
  EXPECT_EQ(r["from_slice"], "eMBB");
  EXPECT_DOUBLE_EQ(r["effective_in_s"].get<double>(), 0.25);
  ASSERT_EQ(rig.probe.slice_requests.size(), 1u);
  EXPECT_EQ(rig.probe.slice_requests[0].slice, "URLLC");
  EXPECT_EQ(rig.probe.slice_requests[0].requester, "tool_server");
  const auto same = rig.result(mcp("switch_network_slice", {{"slice", "eMBB"}}));
  EXPECT_EQ(same["status"], "active");
  EXPECT_EQ(same["note"], "already active");
  const auto bad = rig.result(mcp("switch_network_slice", {{"slice", "5G"}}));
  EXPECT_EQ(bad["status"], "error");
  EXPECT_EQ(rig.probe.slice_requests.size(), 2u);
}

TEST(ToolServerQueries, ARefusedOrUnansweredSliceSwitchSaysSo) {
  Rig refusing(test::test_config(), {}, test::SliceResponder::kRefuse);
  const auto refused = refusing.result(mcp("switch_network_slice", {{"slice", "mMTC"}}));
  EXPECT_EQ(refused["status"], "refused");
  EXPECT_EQ(refused["reason"], "slice mMTC is not offered here");

  Rig silent(test::test_config(), {}, test::SliceResponder::kSilent);
  const double t0 = silent.now_s();
  const auto timeout = silent.result(mcp("switch_network_slice", {{"slice", "URLLC"}}));
  EXPECT_EQ(timeout["status"], "timeout");
  EXPECT_NEAR(silent.now_s() - t0, 2.0, 0.02);
  EXPECT_EQ(silent.server.counters().get("timeouts"), 1u);
}

TEST(ToolServerQueries, MalformedLinkMessagesAreDroppedAndCounted) {
  Rig rig;
  const auto raw = [](const std::string& kind, const std::string& text) {
    a3lcm::link_message_t m{};
    m.kind = kind;
    m.sender = "agent";
    m.payload.assign(text.begin(), text.end());
    m.payload_length = static_cast<int32_t>(m.payload.size());
    return m;
  };
  rig.send_raw(raw("mcp_call", "{not json"));
  rig.send_raw(raw("mcp_call", R"({"action_index": 0, "action": {"type": "mcp", "name": "hold"}})"));
  rig.send_raw(raw("mcp_call", R"({"turn": 1, "action_index": 0, "action": "hold"})"));
  rig.send_raw(raw("telepathy", R"({"turn": 1, "action_index": 0, "action": {}})"));
  rig.run_for(1.0);
  EXPECT_TRUE(rig.probe.down.empty());
  EXPECT_TRUE(rig.fc.commands.empty());
  EXPECT_EQ(rig.server.counters().get("malformed_dropped"), 4u);
  EXPECT_EQ(rig.server.counters().get("link_messages"), 4u);
  // The server keeps working.
  const auto r = rig.result(mcp("check_geofence", {{"x", 100.0}, {"y", 100.0}, {"z", 30.0}}));
  EXPECT_EQ(r["status"], "inside_geofence");
}

TEST(ToolServerQueries, ObservationsComeInTheOrderOfTheActions) {
  Rig rig;
  rig.take_off(30.0);
  const std::size_t before = rig.probe.down.size();
  rig.send(mcp("set_waypoint", {{"x", 60.0}, {"y", 20.0}, {"z", 30.0}}), 7, 0);  // waits for the fc
  rig.send(mcp("read_telemetry"), 7, 1);
  rig.send(test::a2a("request_weather_update", "weather_service"), 7, 2);
  rig.send(mcp("check_geofence"), 7, 3);
  rig.run_for(1.0);
  ASSERT_EQ(rig.probe.down.size(), before + 4);
  for (int i = 0; i < 4; ++i) {
    const auto& d = rig.probe.down[before + static_cast<std::size_t>(i)];
    EXPECT_EQ(d.turn, 7);
    EXPECT_EQ(d.action_index, i);
  }
  EXPECT_EQ(rig.probe.down[before].obs["tool"], "set_waypoint");
  EXPECT_EQ(rig.probe.down[before + 2].obs["task"], "request_weather_update");
  EXPECT_EQ(rig.probe.down[before + 1].obs["result"]["mode"], "goto") << "read after the waypoint was accepted";
  for (std::size_t i = 1; i < rig.probe.down.size(); ++i) {
    EXPECT_GT(rig.probe.down[i].message.message_id, rig.probe.down[i - 1].message.message_id);
  }
}

// One mission's worth of calls; what the server said and commanded, with the times.
std::string run_mission() {
  Rig rig;
  rig.take_off(30.0);
  rig.result(mcp("execute_maneuver", {{"maneuver", "survey"},
                                      {"area", {{40, 40}, {120, 40}, {120, 90}, {40, 90}}},
                                      {"spacing_m", 20.0},
                                      {"capture", true}}));
  rig.run_for(10.0);
  rig.result(mcp("capture_image"));
  rig.result(mcp("read_telemetry"));
  rig.run_for(60.0);
  rig.result(mcp("return_to_home"));
  rig.run_for(60.0);
  std::string out;
  for (const auto& d : rig.probe.down) out += std::to_string(d.t_s) + " " + d.obs.dump() + "\n";
  for (const auto& c : rig.fc.commands) {
    out += std::to_string(c.utime_us) + " cmd " + std::to_string(c.command) + " " + std::to_string(c.target_W_m[0]) +
           "\n";
  }
  for (const auto& e : rig.probe.payload) out += std::to_string(e.utime_us) + " " + e.item_id + "\n";
  return out;
}

TEST(ToolServerQueries, TheSameCallsGiveTheSameEpisodeInVirtualTime) {
  const std::string a = run_mission(), b = run_mission();
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, b);
}

TEST(ToolServerQueries, BadScenarioInputIsRefusedNamingTheField) {
  auto config = test::test_config();
  config.sensors.payloads.push_back({"rgb", "camera", "", 0.0});
  EXPECT_THROW(
      {
        try {
          ToolServerNode node(config);
        } catch (const std::invalid_argument& e) {
          EXPECT_STREQ(e.what(), "uav.payloads[2].id: 'rgb' is also a sensor name");
          throw;
        }
      },
      std::invalid_argument);
  config = test::test_config();
  config.env.wind_mps = -3.0;
  EXPECT_THROW(ToolServerNode{config}, std::invalid_argument);
  config = test::test_config();
  config.gate.nfz_margin_m = -1.0;
  try {
    ToolServerNode node(config);
    ADD_FAILURE() << "a negative margin was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ToolServerConfig.gate.nfz_margin_m"), std::string::npos) << e.what();
  }
  config = test::test_config();
  config.energy.hover_power_w = 0.0;
  EXPECT_THROW(ToolServerNode{config}, std::invalid_argument);
  config = test::test_config();
  TrafficPlan plan;
  plan.id = "uav-2";
  plan.path = {{10.0, Eigen::Vector3d::Zero()}, {5.0, Eigen::Vector3d::Ones()}};
  config.airspace.traffic = {plan};
  try {
    ToolServerNode node(config);
    ADD_FAILURE() << "times going backwards were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "traffic[0].path[1].t_s must increase");
  }
}

}  // namespace
}  // namespace a3::vehicle
