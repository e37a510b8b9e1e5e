// The episode writer marks final_state.uav.landed only when the vehicle ended on the ground,
// disarmed, whole and within the return-and-land radius of home; with a 10 m altitude floor the
// marked episode keeps SP 1 and an unmarked one loses the altitude penalty.
#include <gtest/gtest.h>

#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/pillars.hpp"
#include "rigs/outputs/episode_writer.hpp"

namespace a3::rigs {
namespace {

Scenario home_under_a_floor() {
  Scenario s;
  s.name = "landing";
  s.initial_state = {
      {"domain", "uav"},
      {"time_s", 0.0},
      {"env", {{"weather", "clear"}, {"wind_mps", 3.0}, {"wind_dir_deg", 90.0}}},
      {"airspace", {{"alt_bounds", {10.0, 120.0}}}},
      {"uav", {{"pose", {{"x", 100.0}, {"y", 100.0}, {"z", 0.0}, {"yaw", 90.0}}}, {"energy", {{"battery_pct", 100.0}}}}},
      {"policy", {{"alt_bounds", {10.0, 120.0}}}},
      {"safety_flags", {{"nfz_violation", false}, {"separation_breach", false}}}};
  s.mission.home_W_m = {100.0, 100.0, 0.0};
  agent::Objective home;
  home.id = "home";
  home.type = agent::ObjectiveType::kReturnAndLand;
  home.radius_m = 5.0;
  s.mission.objectives.push_back(home);
  return s;
}

// Ten alternating turns, each agent turn with one answered action.
RecordedEpisode ended_at(double x_m, double y_m, double z_m) {
  RecordedEpisode rec;
  for (int i = 0; i < 10; ++i) {
    const bool agent = i % 2 == 0;
    nlohmann::json turn = {{"turn", i + 1}, {"speaker", agent ? "agent" : "user"}, {"intent", "x"},
                           {"actions", nlohmann::json::array()}, {"obs", nlohmann::json::array()},
                           {"net", {{"slice", "URLLC"}, {"lat_ms", 7.0}, {"jitter_ms", 1.0}, {"loss_pct", 0.0},
                                    {"throughput_mbps", 90.0}, {"edge_load", 0.3}}}};
    if (agent) {
      turn["actions"].push_back({{"type", "mcp"}, {"name", "read_telemetry"}, {"args", nlohmann::json::object()}});
      turn["obs"].push_back({{"tool", "read_telemetry"}, {"result", "ok"}});
    }
    rec.turns.push_back(turn);
  }
  rec.have_state = true;
  rec.last_state.p_W_m[0] = x_m;
  rec.last_state.p_W_m[1] = y_m;
  rec.last_state.p_W_m[2] = z_m;
  rec.last_state.q_WB[0] = 1.0;
  rec.last_state.battery_pct = 80.0;
  rec.last_state.on_ground = z_m < 0.1;
  rec.objectives_all_done = true;
  return rec;
}

nlohmann::json episode(const RecordedEpisode& rec) {
  RunOptions o;
  o.runtime = Runtime::kVirtual;
  RunFacts f;
  f.status = "completed";
  f.agent_name = "scripted";
  return build_episode(home_under_a_floor(), o, rec, f);
}

double sp_of(const nlohmann::json& e) {
  const eval::ScoringProfile profile = eval::release_profile();
  const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  eval::EpisodeReader reader(validator, profile);
  const eval::EpisodeCheck check = reader.check_text(e.dump());
  EXPECT_EQ(check.status, eval::EpisodeStatus::kValid);
  return eval::score_pillars(check.facts, profile, 10.0).sp;
}

TEST(RigLandingMarker, ALandingAtHomeIsMarkedAndKeepsSafety) {
  const nlohmann::json e = episode(ended_at(101.0, 102.0, 0.0));
  const nlohmann::json& landed = e["final_state"]["uav"]["landed"];
  EXPECT_EQ(landed["site"], "home");
  EXPECT_EQ(landed["objective"], "home");
  EXPECT_NEAR(landed["distance_m"].get<double>(), std::sqrt(5.0), 1e-9);
  EXPECT_DOUBLE_EQ(sp_of(e), 1.0);
}

TEST(RigLandingMarker, NoMarkerOutsideTheReturnRadius) {
  const nlohmann::json e = episode(ended_at(106.0, 100.0, 0.0));  // landed 6 m away, radius 5
  EXPECT_FALSE(e["final_state"]["uav"].contains("landed"));
  EXPECT_DOUBLE_EQ(sp_of(e), 0.75);
}

TEST(RigLandingMarker, NoMarkerWhenArmedCrashedOrInTheAir) {
  RecordedEpisode armed = ended_at(100.0, 100.0, 0.0);
  armed.last_fc.armed = true;
  EXPECT_FALSE(episode(armed)["final_state"]["uav"].contains("landed"));
  RecordedEpisode crashed = ended_at(100.0, 100.0, 0.0);
  crashed.last_state.crashed = true;
  EXPECT_FALSE(episode(crashed)["final_state"]["uav"].contains("landed"));
  EXPECT_FALSE(episode(ended_at(100.0, 100.0, 3.0))["final_state"]["uav"].contains("landed"));
}

}  // namespace
}  // namespace a3::rigs
