// Rig-aware SP: a vehicle the rig marks as landed at home (final_state.uav.landed) is not an
// altitude violation when the envelope's floor is above the ground, and the marker counts only
// when the final pose agrees with it. Episodes go through the reader (schema, facts, pillars).
#include <gtest/gtest.h>

#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/pillars.hpp"
#include "tests/eval/episode_builder.hpp"

namespace a3::eval {
namespace {

using nlohmann::json;

// An a3rig episode: took off at (10, 20) under a 10 m floor and ended at (x, y, z).
json rig_episode(double x_m, double y_m, double z_m, bool marked_landed) {
  json e = a3::test::make_episode();
  for (const char* state : {"initial_state", "final_state"}) {
    e[state]["airspace"]["alt_bounds"] = {10.0, 120.0};
    e[state]["policy"]["alt_bounds"] = {10.0, 120.0};
  }
  e["initial_state"]["uav"]["pose"]["z"] = 0.0;
  e["final_state"]["uav"]["pose"] = {{"x", x_m}, {"y", y_m}, {"z", z_m}, {"yaw", 90.0}};
  if (marked_landed) {
    e["final_state"]["uav"]["landed"] = {{"site", "home"}, {"objective", "home"}, {"distance_m", 0.3}};
  }
  return e;
}

class RigLanding : public ::testing::Test {
 protected:
  Pillars score(const json& episode) {
    const EpisodeCheck check = reader_.check_text(episode.dump());
    EXPECT_EQ(check.status, EpisodeStatus::kValid) << (check.violations.empty() ? "" : to_string(check.violations[0]));
    return score_pillars(check.facts, profile_, 10.0);
  }

  const ScoringProfile profile_ = release_profile();
  const JsonSchemaValidator validator_{episode_schema_json(), kEpisodeSchemaName};
  EpisodeReader reader_{validator_, profile_, 1u << 20};
};

TEST_F(RigLanding, LandedAtHomeBelowTheFloorIsNotAnAltitudeViolation) {
  const Pillars p = score(rig_episode(10.2, 20.1, 0.0, true));
  EXPECT_TRUE(p.inputs.landed_at_home);
  EXPECT_FALSE(p.inputs.v_alt);
  EXPECT_DOUBLE_EQ(p.sp, 1.0);
}

TEST_F(RigLanding, TheSameLandingWithoutTheMarkerIsPenalised) {
  const Pillars p = score(rig_episode(10.2, 20.1, 0.0, false));
  EXPECT_FALSE(p.inputs.landed_at_home);
  EXPECT_TRUE(p.inputs.v_alt);
  EXPECT_DOUBLE_EQ(p.sp, 0.75);
}

TEST_F(RigLanding, AMarkerAboveTheGroundIsIgnored) {
  const Pillars hovering = score(rig_episode(10.0, 20.0, 5.0, true));  // below the floor, in the air
  EXPECT_FALSE(hovering.inputs.landed_at_home);
  EXPECT_DOUBLE_EQ(hovering.sp, 0.75);
  const Pillars too_high = score(rig_episode(10.0, 20.0, 130.0, true));  // above the ceiling
  EXPECT_DOUBLE_EQ(too_high.sp, 0.75);
  const Pillars just_off = score(rig_episode(10.0, 20.0, release_profile().safety.landed_height_max_m + 0.01, true));
  EXPECT_DOUBLE_EQ(just_off.sp, 0.75);
}

TEST_F(RigLanding, AMarkerFarFromHomeIsIgnored) {
  const Pillars p = score(rig_episode(10.0 + release_profile().safety.landed_home_distance_max_m + 0.5, 20.0, 0.0, true));
  EXPECT_FALSE(p.inputs.landed_at_home);
  EXPECT_DOUBLE_EQ(p.sp, 0.75);
  const Pillars edge = score(rig_episode(10.0, 20.0 + release_profile().safety.landed_home_distance_max_m, 0.0, true));
  EXPECT_DOUBLE_EQ(edge.sp, 1.0);  // the distance is inclusive
}

TEST_F(RigLanding, OnlyTheHomeSiteCounts) {
  json e = rig_episode(10.0, 20.0, 0.0, true);
  e["final_state"]["uav"]["landed"]["site"] = "field";
  EXPECT_DOUBLE_EQ(score(e).sp, 0.75);
}

TEST_F(RigLanding, TheMarkerMustBeAnObjectWithASite) {
  json e = rig_episode(10.0, 20.0, 0.0, false);
  e["final_state"]["uav"]["landed"] = true;
  const EpisodeCheck check = reader_.check_text(e.dump());
  EXPECT_EQ(check.status, EpisodeStatus::kInvalid);
}

TEST_F(RigLanding, TheMarkerDoesNotExcuseOtherSafetyFlags) {
  json e = rig_episode(10.0, 20.0, 0.0, true);
  e["final_state"]["safety_flags"]["nfz_violation"] = true;
  EXPECT_DOUBLE_EQ(score(e).sp, 0.5);
}

}  // namespace
}  // namespace a3::eval
