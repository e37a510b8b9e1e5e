// The swarm's conflict prediction allows our vehicle to run late against its predicted path
// (stops at route waypoints, wind): the closest approach is the nearest over every lateness up
// to own_lateness_s, and the vehicle waits where it is meanwhile. A yielding peer whose climb
// alone is not enough also holds its course until it would pass far enough away, and where no
// plan is enough takes the one that leaves the most room.
#include <gtest/gtest.h>

#include <cmath>

#include "vehicle/swarm_peer.hpp"

namespace a3::vehicle {
namespace {

// Ours: east along y = 0 at 10 m/s from the origin at t = 0. The peer: north along x = 100 at
// 10 m/s, crossing y = 0 at t = 20 — ten seconds after we pass x = 100.
TrafficPlan ours() {
  TrafficPlan p;
  p.id = "self";
  p.path = {{0.0, Eigen::Vector3d(0, 0, 40)}, {30.0, Eigen::Vector3d(300, 0, 40)}};
  return p;
}
TrafficPlan crossing_peer() {
  TrafficPlan p;
  p.id = "peer";
  p.path = {{0.0, Eigen::Vector3d(100, -200, 40)}, {40.0, Eigen::Vector3d(100, 200, 40)}};
  return p;
}

TEST(SwarmLateness, OnTimeTheCrossingIsClear) {
  // (10t - 100, 10t - 200) is shortest at t = 15: 50 √2 m.
  EXPECT_NEAR(closest_approach_running_late(ours(), crossing_peer(), 0.0, 60.0, 0.0).distance_m, 50.0 * std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(closest_approach(ours(), crossing_peer(), 0.0, 60.0).distance_m, 50.0 * std::sqrt(2.0), 1e-6);
}

TEST(SwarmLateness, FiveSecondsLateHalvesIt) {
  // Five seconds late: (10t - 150, 10t - 200), shortest at t = 17.5: 25 √2 m.
  EXPECT_NEAR(closest_approach_running_late(ours(), crossing_peer(), 0.0, 60.0, 5.0).distance_m, 25.0 * std::sqrt(2.0), 1e-6);
}

TEST(SwarmLateness, TenSecondsLateIsACollisionCourse) {
  const Approach a = closest_approach_running_late(ours(), crossing_peer(), 0.0, 60.0, 15.0);
  EXPECT_LT(a.distance_m, 1e-6);
  EXPECT_NEAR(a.t_s, 20.0, 1e-6);
  EXPECT_NEAR(a.a_W_m.x(), 100.0, 1e-6);
}

TEST(SwarmLateness, ALateVehicleWaitsWhereItIsNotWhereItWasPlannedToBe) {
  // From t0 = 5 s, ours is at (50, 0): ten seconds late it is still there at t = 15, not back at 0.
  TrafficPlan still_peer;
  still_peer.id = "still";
  still_peer.path = {{0.0, Eigen::Vector3d(0, 0, 40)}};  // parked at our start point
  const Approach a = closest_approach_running_late(ours(), still_peer, 5.0, 10.0, 10.0);
  EXPECT_NEAR(a.distance_m, 50.0, 1e-6);
}

// A peer on a collision course crossing our path 10 s from now: its 40 m climb at 2.5 m/s has
// reached only 25 m by then.
nlohmann::json yield_answer(double max_hold_s) {
  TrafficPlan peer;
  peer.id = "peer";
  peer.path = {{0.0, Eigen::Vector3d(100, -100, 40)}, {20.0, Eigen::Vector3d(100, 100, 40)}};
  peer.min_separation_m = 30.0;
  peer.yield_climb_m = 40.0;
  SwarmConfig config;
  config.max_yield_hold_s = max_hold_s;
  SwarmPeer swarm({peer}, config);
  SelfView self;
  self.known = true;
  self.p_W_m = Eigen::Vector3d(0, 0, 40);
  self.predicted = ours();
  self.basis = TrackBasis::kRoute;
  return swarm.collision_avoidance(self, {{"request", "yield"}}).payload;
}

TEST(SwarmYield, AClimbTooSlowForTheConflictIsHelpedByHoldingTheCourse) {
  const nlohmann::json answer = yield_answer(60.0);
  const nlohmann::json& peer = answer["peers"][0];
  EXPECT_EQ(peer["action"], "yielding") << answer.dump();
  EXPECT_GT(peer["hold_s"].get<double>(), 0.0) << answer.dump();
  EXPECT_GE(peer["predicted_separation_after_m"].get<double>(), 40.0) << answer.dump();
  EXPECT_EQ(answer["recommendation"], "proceed: the peers in conflict are yielding");
}

TEST(SwarmYield, WithoutHoldingTheClimbAloneLeavesABreachAndSaysGiveWay) {
  const nlohmann::json answer = yield_answer(0.0);
  const nlohmann::json& peer = answer["peers"][0];
  EXPECT_EQ(peer["hold_s"].get<double>(), 0.0);
  EXPECT_LT(peer["predicted_separation_after_m"].get<double>(), 30.0) << answer.dump();
  EXPECT_EQ(answer["recommendation"], "give_way: hold or change altitude");
}

// A slow peer just past our path, moving off it at 2 m/s: holding its course would keep it
// in front of us, so when no plan gives the wanted separation it yields the way that gives the
// most (the climb alone), never the longest hold.
TEST(SwarmYield, WhenNoPlanIsEnoughThePeerYieldsTheWayThatLeavesTheMostRoom) {
  TrafficPlan peer;
  peer.id = "heli";
  peer.path = {{0.0, Eigen::Vector3d(60, 5, 40)}, {100.0, Eigen::Vector3d(60, 205, 40)}};
  peer.min_separation_m = 30.0;
  peer.yield_climb_m = 40.0;
  SwarmPeer swarm({peer}, SwarmConfig{});
  SelfView self;
  self.known = true;
  self.p_W_m = Eigen::Vector3d(0, 0, 40);
  self.predicted = ours();
  self.basis = TrackBasis::kRoute;
  const nlohmann::json answer = swarm.collision_avoidance(self, {{"request", "yield"}}).payload;
  const nlohmann::json& entry = answer["peers"][0];
  ASSERT_EQ(entry["action"], "yielding") << answer.dump();
  EXPECT_EQ(entry["hold_s"].get<double>(), 0.0) << answer.dump();
  // Climbing while it flies on: about 17 m along and 15 m up when we pass; holding: 5 m and 15 m.
  EXPECT_GT(entry["predicted_separation_after_m"].get<double>(), 20.0) << answer.dump();
  EXPECT_EQ(answer["recommendation"], "give_way: hold or change altitude");
}

TEST(SwarmLateness, TheConfigRefusesANegativeOrHugeLateness) {
  SwarmConfig c;
  c.own_lateness_s = -1.0;
  EXPECT_THROW(c.validate("swarm"), std::invalid_argument);
  c.own_lateness_s = 1e9;
  EXPECT_THROW(c.validate("swarm"), std::invalid_argument);
  c.own_lateness_s = 15.0;
  EXPECT_NO_THROW(c.validate("swarm"));
  c.max_yield_hold_s = -5.0;
  EXPECT_THROW(c.validate("swarm"), std::invalid_argument);
}

}  // namespace
}  // namespace a3::vehicle
