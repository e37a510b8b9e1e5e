// The scripted reference agent on mission shapes that once broke it (tests/data/scenarios/),
// flown in virtual time: a delivery behind a no-fly zone (the ground station's detour must keep
// the descent to drop height), three image points with no spare turn (no capture on the climb
// at home), and a 15 m objective flown with 20 s of think time while the link degrades on the
// approach (a lost command is sent again; a capture only within the objective's own radius).
// Each must succeed with α³ ≥ 0.9, and every capture must lie within its objective's radius.
// A survey then a thermal search with a no-fly zone beside the way home in a gusting wind, at
// the think times that once flew the return 3.3 m into the zone, keeps clear of it by more than
// the flight controller's brake margin (the routes' clearance covers the tracking error). A
// heavy-lift vehicle imaging three points past a polygon zone, with a degradation and a
// helicopter shuttling past the first, checks the way ahead with the swarm in every turn and never
// breaches its separation (at 30 s of think time the helicopter's alert came 3.5 s before the
// conflict).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

std::string shape_file(const std::string& name) {
  return (a3::test::source_dir() / "tests" / "data" / "scenarios" / (name + ".json")).string();
}

struct Flown {
  RunResult result;
  a3::test::Scored scored;
};

Flown fly(const std::string& shape, const std::string& think_time = "0", int max_turns = 0) {
  RunOptions o = a3::test::virtual_run(shape_file(shape), "reference-" + shape);
  o.think_time = think_time;
  if (max_turns > 0) o.max_turns = max_turns;
  Flown f{a3::test::run(o), {}};
  f.scored = a3::test::score(f.result.episode);
  std::filesystem::remove_all(o.out_dir);
  return f;
}

void expect_success(const Flown& f) {
  const nlohmann::json& e = f.result.episode;
  EXPECT_EQ(f.result.status, "completed");
  EXPECT_TRUE(e.value("success", false)) << e["_rig"]["objectives"].dump();
  ASSERT_TRUE(f.scored.valid) << f.scored.problems;
  const eval::Pillars& p = f.scored.pillars;
  EXPECT_GE(p.alpha3, 0.9) << "TO " << p.to << " SP " << p.sp << " TC " << p.tc << " IQ " << p.iq << " NR " << p.nr
                           << " CC " << p.cc;
  EXPECT_NEAR(e["final_state"]["uav"]["pose"]["z"].get<double>(), 0.0, 0.05);
}

// Every capture_image observation (true pose at capture) lies within the radius of an image
// point of its sensor; returns how many captures there were.
int expect_captures_within_radius(const Flown& f, const std::string& shape) {
  const Scenario s = load_scenario(shape_file(shape), ".");
  int captures = 0;
  for (const auto& turn : f.result.episode["dialogue"]) {
    for (const auto& o : turn["obs"]) {
      if (!o.is_object() || o.value("tool", "") != "capture_image") continue;
      const auto& r = o["result"];
      EXPECT_EQ(r.value("status", ""), "captured") << r.dump();
      if (!r.contains("pose")) continue;
      ++captures;
      const Eigen::Vector2d p(r["pose"]["x"].get<double>(), r["pose"]["y"].get<double>());
      double nearest_m = 1e9, radius_m = 0.0;
      for (const auto& obj : s.mission.objectives) {
        if (obj.type != agent::ObjectiveType::kImagePoint || obj.sensor != r.value("sensor", "")) continue;
        if ((p - obj.point).norm() < nearest_m) {
          nearest_m = (p - obj.point).norm();
          radius_m = obj.radius_m;
        }
      }
      EXPECT_LE(nearest_m, radius_m) << "turn " << turn["turn"] << ": captured at (" << p.x() << ", " << p.y() << ")";
    }
  }
  return captures;
}

TEST(ReferenceAgent, DeliversBehindANoFlyZoneAlongTheDetourAndStillDescends) {
  const Flown f = fly("delivery-behind-nfz");
  expect_success(f);
  // The leg flown is the planner's detour (more than the two points of the direct leg) and
  // ends with the descent to drop height.
  bool detour_with_descent = false;
  for (const auto& turn : f.result.episode["dialogue"]) {
    for (const auto& a : turn["actions"]) {
      if (a.value("name", "") != "navigate_to") continue;
      const auto& w = a["args"]["waypoints"];
      detour_with_descent |= w.size() > 2 && w.back()[2].get<double>() <= 8.0 && w[w.size() - 2][2].get<double>() >= 40.0;
    }
  }
  EXPECT_TRUE(detour_with_descent);
  EXPECT_FALSE(f.result.episode["final_state"]["safety_flags"]["nfz_violation"].get<bool>());
}

TEST(ReferenceAgent, ImagesThreePointsWithNoSpareTurnWithoutCapturingOnTheClimb) {
  const Flown f = fly("three-objectives-tight");
  expect_success(f);
  EXPECT_EQ(expect_captures_within_radius(f, "three-objectives-tight"), 3);
  EXPECT_LE(f.result.episode["dialogue"].size(), 12u);
}

TEST(ReferenceAgent, CapturesASmallObjectiveOnlyWithinItsRadiusWhenThinkingSlowlyOnALossyLink) {
  const Flown f = fly("small-radius-slow-think", "20");
  expect_success(f);
  EXPECT_EQ(expect_captures_within_radius(f, "small-radius-slow-think"), 1);
}

TEST(ReferenceAgent, SurveyThenSearchKeepsClearOfTheZoneBesideTheWayHomeInGustsAtEveryThinkTime) {
  for (const std::string think : {"0", "10", "30"}) {
    SCOPED_TRACE("think time " + think + " s");
    const Flown f = fly("survey-search-nfz-gusts", think);
    expect_success(f);
    const nlohmann::json& rig = f.result.episode["_rig"];
    EXPECT_TRUE(rig["safety_events"].empty()) << rig["safety_events"].dump();
    ASSERT_EQ(rig["no_fly_zone_clearance"].size(), 1u) << rig["no_fly_zone_clearance"].dump();
    const double closest_m = rig["no_fly_zone_clearance"][0]["closest_m"].get<double>();
    std::cout << "think " << think << " s: closest to the school zone " << closest_m << " m\n";
    EXPECT_GT(closest_m, 2.0);  // bridge::FcFailsafeParams::nfz_stop_margin_m: the brake never had to act
  }
}

TEST(ReferenceAgent, ThreeImagesPastAZoneWithAHelicopterAboutKeepSeparationAtEveryThinkTime) {
  for (const std::string think : {"0", "10", "30"}) {
    SCOPED_TRACE("think time " + think + " s");
    // 20 turns: longer than the corpus's 8–12, so the episode is flown and judged but not scored.
    const Flown f = fly("heavy-lift-three-images-traffic", think, 20);
    EXPECT_EQ(f.result.status, "completed");
    EXPECT_TRUE(f.result.episode.value("success", false)) << f.result.episode["_rig"]["objectives"].dump();
    const nlohmann::json& rig = f.result.episode["_rig"];
    for (const auto& event : rig["safety_events"]) {
      EXPECT_NE(event.value("kind", ""), "separation_breach") << event.dump();
      EXPECT_NE(event.value("kind", ""), "nfz_intrusion") << event.dump();
    }
    EXPECT_EQ(rig["agent_faults"], nlohmann::json::array());
  }
}

// traffic-conflict at the think times where every seed of the 20-seed sweep breached the
// patrol's separation before the swarm predicted our vehicle climbing while it flies (it
// predicted the first leg 30 s late, beyond the lateness it allows): no breach now.
TEST(ReferenceAgent, TrafficConflictKeepsSeparationAtTheThinkTimesThatBreachedIt) {
  for (const std::string think : {"10", "120"}) {
    for (uint64_t seed = 1; seed <= 5; ++seed) {
      SCOPED_TRACE("think time " + think + " s, seed " + std::to_string(seed));
      RunOptions o = a3::test::virtual_run("traffic-conflict", "reference-traffic-" + think + "-" + std::to_string(seed));
      o.think_time = think;
      o.seed = seed;
      const RunResult r = a3::test::run(o);
      std::filesystem::remove_all(o.out_dir);
      EXPECT_EQ(r.status, "completed");
      EXPECT_TRUE(r.episode.value("success", false));
      for (const auto& event : r.episode["_rig"]["safety_events"]) {
        EXPECT_NE(event.value("kind", ""), "separation_breach") << event.dump();
      }
    }
  }
}

}  // namespace
}  // namespace a3::rigs
