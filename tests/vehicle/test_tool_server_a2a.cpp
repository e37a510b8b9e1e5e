// The simulated A2A peers behind the tool server, in virtual time: collision_avoidance making
// a conflicting peer yield (its published path changes) or telling us to give way,
// swarm_status_check, swarm_formation, request_weather_update, path_plan around the no-fly
// zones, handover_data charging the handed-over images to the downlink, the traffic on
// A3_TRAFFIC at 10 Hz, and errors for unknown tasks and wrong peers.
#include <gtest/gtest.h>

#include "tests/vehicle/vehicle_test_util.hpp"

namespace a3::vehicle {
namespace {

using test::a2a;
using test::mcp;
using test::Rig;

// uav-2 holds at (380, 100, 40) until t = 40 s, then flies west along y = 100 at 5 m/s;
// uav-3 flies south along x = 100 from t = 0, crossing y = 100 at t = 36 s.
ToolServerConfig config_with_traffic(bool uav2_yields = true) {
  auto c = test::test_config();
  TrafficPlan uav2;
  uav2.id = "uav-2";
  uav2.path = {{40.0, Eigen::Vector3d(380, 100, 40)}, {112.0, Eigen::Vector3d(20, 100, 40)}};
  uav2.min_separation_m = 30.0;
  uav2.yields_when_asked = uav2_yields;
  uav2.yield_climb_m = 40.0;
  TrafficPlan uav3;
  uav3.id = "uav-3";
  uav3.path = {{0.0, Eigen::Vector3d(100, 280, 40)}, {52.0, Eigen::Vector3d(100, 20, 40)}};
  c.airspace.traffic = {uav2, uav3};
  return c;
}

// Airborne at (20, 100, 40) at about t = 38 s.
void get_to_start(Rig& rig) {
  rig.take_off(40.0);
  rig.fly_to(Eigen::Vector3d(20, 100, 40));
}

const nlohmann::json& peer_entry(const nlohmann::json& payload, const std::string& id) {
  for (const auto& p : payload["peers"]) {
    if (p["id"] == id) return p;
  }
  static const nlohmann::json none;
  ADD_FAILURE() << "no entry for " << id << " in " << payload.dump();
  return none;
}

std::vector<a3lcm::traffic_state_t> traffic_of(const Rig& rig, const std::string& id) {
  std::vector<a3lcm::traffic_state_t> out;
  for (const auto& t : rig.probe.traffic) {
    if (t.id == id) out.push_back(t);
  }
  return out;
}

TEST(ToolServerA2a, CollisionAvoidanceMakesAConflictingPeerYieldAndItsPathChanges) {
  Rig rig(config_with_traffic());
  get_to_start(rig);
  const auto clear = rig.call(a2a("collision_avoidance", "uav_swarm_agent", {{"request", "yield"}}));
  EXPECT_EQ(clear["from"], "uav_swarm_agent");
  EXPECT_EQ(clear["status"], "ok");
  EXPECT_EQ(clear["payload"]["clear"], true) << "holding at the start, nobody comes within 40 m in 60 s: "
                                              << clear.dump();
  EXPECT_EQ(clear["payload"]["recommendation"], "proceed");

  rig.result(mcp("navigate_to", {{"waypoints", {{380, 100, 40}}}}));
  rig.run_for(1.0);
  const auto query = rig.call(a2a("collision_avoidance", "uav_swarm_agent", {{"request", "query"}}));
  const auto& q = peer_entry(query["payload"], "uav-2");
  EXPECT_EQ(q["conflict"], true) << query.dump();
  EXPECT_LT(q["predicted_min_separation_m"].get<double>(), 1.0) << "head-on at the same altitude";
  EXPECT_NEAR(q["time_to_closest_s"].get<double>(), 35.5, 1.0);
  EXPECT_EQ(q["action"], "none");
  EXPECT_EQ(peer_entry(query["payload"], "uav-3")["conflict"], false);
  EXPECT_EQ(rig.server.swarm().peers()[0].yielded, false) << "a query changes nothing";

  const double asked_at = rig.now_s();
  const auto obs = rig.call(a2a("collision_avoidance", "uav_swarm_agent", {{"request", "yield"}}));
  const auto& e = peer_entry(obs["payload"], "uav-2");
  EXPECT_EQ(e["action"], "yielding") << obs.dump();
  EXPECT_DOUBLE_EQ(e["climb_m"].get<double>(), 40.0);
  EXPECT_DOUBLE_EQ(e["new_altitude_m"].get<double>(), 80.0);
  EXPECT_GE(e["predicted_separation_after_m"].get<double>(), 30.0);
  EXPECT_EQ(obs["payload"]["conflicts"], 1);
  EXPECT_EQ(obs["payload"]["recommendation"], "proceed: the peers in conflict are yielding");

  // Its published path climbs from the moment it was asked, and says it is yielding.
  const std::size_t seen = traffic_of(rig, "uav-2").size();
  rig.run_for(20.0);
  const auto later = traffic_of(rig, "uav-2");
  ASSERT_GT(later.size(), seen + 150);
  const auto& last = later.back();
  EXPECT_EQ(last.status, "yielding");
  EXPECT_NEAR(last.p_W_m[2], 80.0, 1e-6) << "40 m up after 16 s at 2.5 m/s";
  const double t_mid = asked_at + 8.0;
  for (const auto& t : later) {
    if (std::abs(static_cast<double>(t.utime_us) * 1e-6 - t_mid) < 0.05) {
      EXPECT_NEAR(t.p_W_m[2], 60.0, 0.2) << "half-way up after 8 s";
    }
  }
  // Asked again: it has climbed clear and does not climb twice.
  const auto again = rig.call(a2a("collision_avoidance", "uav_swarm_agent"));
  const auto& a = peer_entry(again["payload"], "uav-2");
  EXPECT_NE(a["action"], "yielding") << again.dump();
  EXPECT_NEAR(a["predicted_min_separation_m"].get<double>(), 40.0, 0.1) << "40 m above our path";
  rig.run_for(5.0);
  EXPECT_NEAR(traffic_of(rig, "uav-2").back().p_W_m[2], 80.0, 1e-6);
}

TEST(ToolServerA2a, APeerThatDoesNotYieldTellsUsToGiveWay) {
  Rig rig(config_with_traffic(false));
  get_to_start(rig);
  rig.result(mcp("navigate_to", {{"waypoints", {{380, 100, 40}}}}));
  rig.run_for(1.0);
  const auto obs = rig.call(a2a("collision_avoidance", "uav_swarm_agent", {{"request", "pass"}}));
  const auto& e = peer_entry(obs["payload"], "uav-2");
  EXPECT_EQ(e["conflict"], true);
  EXPECT_EQ(e["action"], "will_not_yield");
  EXPECT_EQ(obs["payload"]["recommendation"], "give_way: hold or change altitude");
  rig.run_for(5.0);
  const auto path = traffic_of(rig, "uav-2");
  EXPECT_DOUBLE_EQ(path.back().p_W_m[2], 40.0) << "its plan is unchanged";
  EXPECT_EQ(path.back().status, "en_route");
}

TEST(ToolServerA2a, TrafficIsPublishedAtTenHertzPerPeer) {
  Rig rig(config_with_traffic());
  const std::size_t before = traffic_of(rig, "uav-3").size();
  rig.run_for(1.0);
  EXPECT_EQ(traffic_of(rig, "uav-3").size() - before, 10u);
  const auto t = traffic_of(rig, "uav-3").back();
  const double now = rig.now_s();
  EXPECT_NEAR(t.p_W_m[1], 280.0 - 5.0 * now, 1e-6);
  EXPECT_NEAR(t.v_W_mps[1], -5.0, 1e-9);
  EXPECT_EQ(t.status, "en_route");
  EXPECT_EQ(traffic_of(rig, "uav-2").back().status, "holding");
}

TEST(ToolServerA2a, SwarmStatusAndFormation) {
  Rig rig(config_with_traffic());
  get_to_start(rig);
  const auto status = rig.call(a2a("swarm_status_check", "uav_swarm_agent"));
  EXPECT_EQ(status["status"], "ok");
  EXPECT_EQ(status["payload"]["count"], 2);
  const auto& u3 = peer_entry(status["payload"], "uav-3");
  EXPECT_NEAR(u3["pose"]["y"].get<double>(), 280.0 - 5.0 * rig.probe.down.back().t_s, 0.01);
  EXPECT_DOUBLE_EQ(u3["heading_deg"].get<double>(), -90.0) << "south, in ENU degrees from east";
  EXPECT_DOUBLE_EQ(u3["speed_mps"].get<double>(), 5.0);
  EXPECT_EQ(peer_entry(status["payload"], "uav-2")["status"], "holding");

  const auto formation = rig.call(a2a("swarm_formation", "uav_swarm_agent", {{"formation", "wedge"}, {"spacing_m", 25}}));
  EXPECT_EQ(formation["status"], "ok") << formation.dump();
  EXPECT_EQ(formation["payload"]["accepted"], nlohmann::json::array({"uav-3"}));
  ASSERT_EQ(formation["payload"]["declined"].size(), 1u);
  EXPECT_EQ(formation["payload"]["declined"][0]["id"], "uav-2");
  EXPECT_NE(formation["payload"]["declined"][0]["reason"].get<std::string>().find("too far: 360 m > 300 m"),
            std::string::npos);
  const auto unknown = rig.call(a2a("swarm_formation", "uav_swarm_agent", {{"formation", "heart"}}));
  EXPECT_EQ(unknown["status"], "error");
  EXPECT_NE(unknown["payload"]["error"].get<std::string>().find("unknown formation 'heart'"), std::string::npos);
}

TEST(ToolServerA2a, WeatherComesFromTheScenariosEnvironment) {
  Rig rig;
  const auto w = rig.call(a2a("request_weather_update", "weather_service"));
  EXPECT_EQ(w["task"], "request_weather_update");
  EXPECT_EQ(w["from"], "weather_service");
  EXPECT_EQ(w["status"], "ok");
  EXPECT_EQ(w["payload"]["weather"], "clear");
  EXPECT_DOUBLE_EQ(w["payload"]["wind_mps"].get<double>(), 6.0);
  EXPECT_DOUBLE_EQ(w["payload"]["wind_dir_deg"].get<double>(), 240.0);
  EXPECT_DOUBLE_EQ(w["payload"]["gust_mps"].get<double>(), 8.4);
  EXPECT_EQ(w["payload"]["advisory"], "ok");

  auto gusty = test::test_config();
  gusty.env.gust_mps = 12.0;
  Rig rig2(gusty);
  EXPECT_EQ(rig2.call(a2a("request_weather_update", "weather_service"))["payload"]["advisory"], "caution");
  auto storm = test::test_config();
  storm.env.weather = "thunderstorm";
  Rig rig3(storm);
  EXPECT_EQ(rig3.call(a2a("request_weather_update", "weather_service"))["payload"]["advisory"], "no_fly");
}

TEST(ToolServerA2a, PathPlanRoutesAroundTheNoFlyZonesAndPassesTheGate) {
  Rig rig;
  rig.take_off(40.0);
  const auto obs = rig.call(a2a("path_plan", "ground_station", {{"start", {20, 20}}, {"goal", {380, 280}}, {"z", 50}}));
  EXPECT_EQ(obs["status"], "ok") << obs.dump();
  const auto& p = obs["payload"];
  EXPECT_EQ(p["avoids"], nlohmann::json::array({"nfz-c"}));
  EXPECT_GT(p["detour_m"].get<double>(), 0.0);
  std::vector<Eigen::Vector3d> waypoints;
  for (const auto& w : p["waypoints"]) waypoints.emplace_back(w[0].get<double>(), w[1].get<double>(), w[2].get<double>());
  ASSERT_GE(waypoints.size(), 2u);
  EXPECT_EQ(waypoints.back(), Eigen::Vector3d(380, 280, 50));
  EXPECT_EQ(rig.server.gate().check_path(Eigen::Vector3d(20, 20, 40), waypoints), "");
  // The agent can fly it as it is.
  nlohmann::json list = nlohmann::json::array();
  for (const auto& w : p["waypoints"]) list.push_back(w);
  EXPECT_EQ(rig.result(mcp("navigate_to", {{"waypoints", list}}))["status"], "accepted");

  const auto into_zone = rig.call(a2a("path_plan", "ground_station", {{"goal", {200, 150}}}));
  EXPECT_EQ(into_zone["status"], "failed");
  EXPECT_NE(into_zone["payload"]["error"].get<std::string>().find("inside no-fly zone nfz-c"), std::string::npos);
  const auto no_goal = rig.call(a2a("path_plan", "ground_station", {{"start", {0, 0}}}));
  EXPECT_EQ(no_goal["status"], "error");
  EXPECT_NE(no_goal["payload"]["error"].get<std::string>().find("payload/goal"), std::string::npos);
}

TEST(ToolServerA2a, HandoverDataChargesTheStoredImagesToTheDownlink) {
  Rig rig;
  rig.result(mcp("capture_image", {{"store_only", true}}));
  rig.result(mcp("capture_image", {{"store_only", true}}));
  rig.result(mcp("capture_image"));  // downlinked already
  const auto obs = rig.call(a2a("handover_data", "ground_station", {{"items", {"img-0001", "img-0003", "img-0042"}}}));
  EXPECT_EQ(obs["status"], "ok") << obs.dump();
  EXPECT_EQ(obs["payload"]["received"], 2);
  EXPECT_EQ(obs["payload"]["bytes"], 3'500'000) << "img-0003 had gone down with its capture";
  EXPECT_EQ(obs["payload"]["unknown"], nlohmann::json::array({"img-0042"}));
  const auto& m = rig.probe.down.back().message;
  EXPECT_EQ(m.payload_size_bytes, 3'500'000 + m.payload_length);
  const auto rest = rig.call(a2a("handover_data", "ground_station"));
  EXPECT_EQ(rest["payload"]["items"], nlohmann::json::array({"img-0002"}));
  EXPECT_EQ(rig.server.counters().get("image_bytes_downlinked"), 3u * 3'500'000u);
}

TEST(ToolServerA2a, UnknownTasksWrongPeersAndBadPayloadsGetErrors) {
  Rig rig;
  const auto unknown = rig.call(a2a("telepathy", "uav_swarm_agent"));
  EXPECT_EQ(unknown["task"], "telepathy");
  EXPECT_EQ(unknown["from"], "uav_swarm_agent");
  EXPECT_EQ(unknown["status"], "error");
  EXPECT_NE(unknown["payload"]["error"].get<std::string>().find("unknown task 'telepathy'"), std::string::npos);
  const auto wrong = rig.call(a2a("request_weather_update", "ground_station"));
  EXPECT_EQ(wrong["from"], "ground_station");
  EXPECT_EQ(wrong["status"], "error");
  EXPECT_EQ(wrong["payload"]["error"],
            "action/to: task 'request_weather_update' is answered by 'weather_service', not 'ground_station'");
  nlohmann::json bad = a2a("collision_avoidance", "uav_swarm_agent");
  bad["payload"] = {{"request", "dance"}};
  const auto bad_obs = rig.call(bad);
  EXPECT_EQ(bad_obs["status"], "error");
  EXPECT_NE(bad_obs["payload"]["error"].get<std::string>().find("payload/request"), std::string::npos);
  EXPECT_EQ(rig.server.counters().get("errors"), 3u);
  EXPECT_TRUE(rig.fc.commands.empty());
}

}  // namespace
}  // namespace a3::vehicle
