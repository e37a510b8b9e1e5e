// The ground station's path_plan for a reference agent's leg: the detour around the no-fly
// zones keeps the requested route altitude and ends with the leg's own descent (a delivery's
// drop height) over the goal; a descent the gate refuses fails the plan with the reason.
#include <gtest/gtest.h>

#include "tests/vehicle/vehicle_test_util.hpp"
#include "vehicle/ground_station.hpp"

namespace a3::vehicle {
namespace {

GroundStation station(const SafetyGate& gate) { return GroundStation(gate, PlannerConfig{}); }

TEST(ReferenceAgentGroundStation, ADetourToAGoalWithItsOwnAltitudeKeepsTheRouteAltitudeAndEndsWithTheDescent) {
  const SafetyGate gate(test::test_airspace(), GateConfig{}, EnergyModel{}, Eigen::Vector3d(20, 20, 0));
  const GroundStation gs = station(gate);
  const PeerAnswer a = gs.path_plan(std::nullopt, {{"start", {20, 20}}, {"goal", {380, 280, 12}}, {"z", 50}});
  ASSERT_EQ(a.status, "ok") << a.payload.dump();
  const auto& w = a.payload["waypoints"];
  ASSERT_GE(w.size(), 3u) << w.dump();  // a detour, then the descent
  EXPECT_EQ(w.back(), nlohmann::json({380, 280, 12}));
  EXPECT_EQ(w[w.size() - 2], nlohmann::json({380, 280, 50}));
  for (std::size_t i = 0; i + 1 < w.size(); ++i) EXPECT_EQ(w[i][2].get<double>(), 50.0) << w.dump();
  EXPECT_FALSE(a.payload["avoids"].empty());
  // Without a route altitude the goal's z is the route's, as before: no extra descent.
  const PeerAnswer level = gs.path_plan(std::nullopt, {{"start", {20, 20}}, {"goal", {380, 280, 50}}});
  ASSERT_EQ(level.status, "ok");
  EXPECT_EQ(level.payload["waypoints"].back(), nlohmann::json({380, 280, 50}));
  EXPECT_EQ(level.payload["waypoints"].size(), w.size() - 1);
}

TEST(ReferenceAgentGroundStation, ADescentBelowTheAltitudeEnvelopeFailsWithTheReason) {
  const SafetyGate gate(test::test_airspace(), GateConfig{}, EnergyModel{}, Eigen::Vector3d(20, 20, 0));
  const PeerAnswer a = station(gate).path_plan(std::nullopt, {{"start", {20, 20}}, {"goal", {380, 280, 2}}, {"z", 50}});
  EXPECT_EQ(a.status, "failed") << a.payload.dump();
  EXPECT_NE(a.payload["error"].get<std::string>().find("descent to the goal's altitude"), std::string::npos);
}

}  // namespace
}  // namespace a3::vehicle
