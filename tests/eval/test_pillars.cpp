// The six pillars and α³ on hand-built episodes, one formula branch at a time (SPEC §2).
#include <gtest/gtest.h>

#include "eval/pillars.hpp"

namespace a3::eval {
namespace {

TurnFacts turn(Speaker speaker, int actions = 0, int matched = 0, int obs = 0,
               const char* slice = "URLLC", double lat_ms = 7, double loss_pct = 0.1,
               double thr_mbps = 90, double edge = 0.3) {
  TurnFacts t;
  t.speaker = speaker;
  t.structured_actions = actions;
  t.matched_actions = matched;
  t.observations = obs;
  t.slice = slice;
  t.lat_ms = lat_ms;
  t.loss_pct = loss_pct;
  t.throughput_mbps = thr_mbps;
  t.edge_load = edge;
  return t;
}

// 10 alternating calm turns; each agent turn has one answered action.
EpisodeFacts calm_episode() {
  EpisodeFacts e;
  for (int i = 0; i < 10; ++i) {
    e.turns.push_back(i % 2 == 0 ? turn(Speaker::kAgent, 1, 1, 1) : turn(Speaker::kUser));
  }
  e.success = true;
  e.final_z_m = 100;
  e.alt_min_m = 30;
  e.alt_max_m = 400;
  e.battery_pct = 50;
  e.total_tokens = 3000;
  return e;
}

const ScoringProfile kRelease = release_profile();

TEST(Pillars, PerfectCalmEpisodeScoresOneEverywhereButCostTerms) {
  const Pillars p = score_pillars(calm_episode(), kRelease, 10.0);
  EXPECT_DOUBLE_EQ(p.to, 1.0);
  EXPECT_DOUBLE_EQ(p.sp, 1.0);
  EXPECT_DOUBLE_EQ(p.tc, 1.0);
  EXPECT_DOUBLE_EQ(p.iq, 1.0);
  EXPECT_DOUBLE_EQ(p.nr, 1.0);  // 0.6*1 + 0.2*1 + 0.2*1, no bonus without hard turns
  EXPECT_DOUBLE_EQ(p.cc, 1.0);  // 3000 tokens, 5 tools: both within budget
  EXPECT_DOUBLE_EQ(p.alpha3, 1.0);
}

TEST(Pillars, TaskOutcomeFollowsSuccess) {
  EpisodeFacts e = calm_episode();
  e.success = false;
  const Pillars p = score_pillars(e, kRelease, 10.0);
  EXPECT_DOUBLE_EQ(p.to, 0.0);
  EXPECT_NEAR(p.alpha3, 0.70, 1e-15);
}

TEST(Pillars, SafetyPenaltiesAddUpAndClampAtZero) {
  EpisodeFacts e = calm_episode();
  e.final_z_m = 400.0;  // bounds are inclusive
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).sp, 1.0);
  e.final_z_m = 400.001;
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).sp, 0.75);
  e.final_z_m = 29.9;
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).sp, 0.75);
  e.battery_pct = 4.99;
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).sp, 0.50);
  e.battery_pct = 5.0;  // not below 5
  e.nfz_violation = true;
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).sp, 0.25);
  e.separation_breach = true;
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).sp, 0.0);  // 1 - .25 - .5 - .5 clamps
  const Pillars p = score_pillars(e, kRelease, 10);
  EXPECT_TRUE(p.inputs.v_alt);
  EXPECT_TRUE(p.inputs.v_nfz);
  EXPECT_TRUE(p.inputs.v_sep);
  EXPECT_FALSE(p.inputs.v_batt);
}

TEST(Pillars, ToolConsistencyIsMatchedOverStructuredAndOneWithoutActions) {
  EpisodeFacts e = calm_episode();
  e.turns[0].matched_actions = 0;
  e.turns[2].structured_actions = 3;
  e.turns[2].matched_actions = 2;
  // 7 actions, 5 matched
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).tc, 5.0 / 7.0);
  for (auto& t : e.turns) t.structured_actions = t.matched_actions = 0;
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).tc, 1.0);
}

TEST(Pillars, InteractionQualityLengthAlternationGrounding) {
  EpisodeFacts e = calm_episode();
  e.turns.push_back(turn(Speaker::kAgent, 1, 1, 1));
  e.turns.push_back(turn(Speaker::kUser));  // T = 12
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).iq, (10.0 / 12.0 + 1.0 + 1.0) / 3.0);
  // Shorter than T_opt: the ratio is capped at 1.
  EpisodeFacts short_one = calm_episode();
  short_one.turns.resize(8);
  EXPECT_DOUBLE_EQ(score_pillars(short_one, kRelease, 10).iq, 1.0);
  // Two agent turns in a row break alternation; an agent turn without observations lowers G.
  EpisodeFacts broken = calm_episode();
  broken.turns[1].speaker = Speaker::kAgent;  // agents: turns 0,1,2,4,6,8 -> 6; with obs: 5
  const Pillars p = score_pillars(broken, kRelease, 10);
  EXPECT_FALSE(p.inputs.alternation_ok);
  EXPECT_EQ(p.inputs.agent_turns, 6);
  EXPECT_EQ(p.inputs.agent_turns_with_obs, 5);
  EXPECT_DOUBLE_EQ(p.iq, (1.0 + 0.0 + 5.0 / 6.0) / 3.0);
  // No agent turn at all: G = 0.
  EpisodeFacts users = calm_episode();
  for (auto& t : users.turns) t.speaker = Speaker::kUser;
  EXPECT_DOUBLE_EQ(score_pillars(users, kRelease, 10).iq, (1.0 + 0.0 + 0.0) / 3.0);
  // A role other than agent/user breaks alternation.
  EpisodeFacts other = calm_episode();
  other.turns[5].speaker = Speaker::kOther;
  EXPECT_FALSE(score_pillars(other, kRelease, 10).inputs.alternation_ok);
}

TEST(Pillars, HardTurnThresholdsAreStrictWhereTheSpecSaysSo) {
  const HardTurnThresholds& h = kRelease.hard;
  EXPECT_FALSE(is_hard_turn(turn(Speaker::kAgent, 0, 0, 0, "URLLC", 40.0), h));
  EXPECT_TRUE(is_hard_turn(turn(Speaker::kAgent, 0, 0, 0, "URLLC", 40.01), h));
  EXPECT_FALSE(is_hard_turn(turn(Speaker::kAgent, 0, 0, 0, "URLLC", 7, 0.99), h));
  EXPECT_TRUE(is_hard_turn(turn(Speaker::kAgent, 0, 0, 0, "URLLC", 7, 1.0), h));
  EXPECT_FALSE(is_hard_turn(turn(Speaker::kAgent, 0, 0, 0, "URLLC", 7, 0.1, 5.0), h));
  EXPECT_TRUE(is_hard_turn(turn(Speaker::kAgent, 0, 0, 0, "URLLC", 7, 0.1, 4.99), h));
  EXPECT_FALSE(is_hard_turn(turn(Speaker::kAgent, 0, 0, 0, "URLLC", 7, 0.1, 90, 0.8), h));
  EXPECT_TRUE(is_hard_turn(turn(Speaker::kAgent, 0, 0, 0, "URLLC", 7, 0.1, 90, 0.81), h));
}

TEST(Pillars, NetworkRobustnessBranches) {
  // 10 turns, 4 hard (h = 0.4 > 0.2: bonus when successful). Hard turns carry no actions:
  // r_h = 0 <= r_n, adapt = 1. Two hard turns on eMBB: slice = 1 - 2/4.
  EpisodeFacts e = calm_episode();
  e.turns[1] = turn(Speaker::kUser, 0, 0, 0, "eMBB", 80);
  e.turns[3] = turn(Speaker::kUser, 0, 0, 0, "eMBB", 7, 2.0);
  e.turns[5] = turn(Speaker::kUser, 0, 0, 0, "mMTC", 7, 0.1, 2.0);
  e.turns[7] = turn(Speaker::kUser, 0, 0, 0, "URLLC", 7, 0.1, 90, 0.9);
  Pillars p = score_pillars(e, kRelease, 10);
  EXPECT_EQ(p.inputs.hard_turns, 4);
  EXPECT_DOUBLE_EQ(p.inputs.nr_base, 1.0 - 0.5 * 0.4);
  EXPECT_DOUBLE_EQ(p.inputs.nr_adapt, 1.0);
  EXPECT_DOUBLE_EQ(p.inputs.nr_slice, 0.5);
  EXPECT_DOUBLE_EQ(p.inputs.nr_bonus, 0.1);
  EXPECT_DOUBLE_EQ(p.nr, 0.6 * 0.8 + 0.2 * 1.0 + 0.2 * 0.5 + 0.1);
  e.success = false;
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).inputs.nr_bonus, 0.0);

  // More actions per hard turn than per normal turn: adapt = clamp01(1.5 - 0.5 r_h/r_n).
  EpisodeFacts busy = calm_episode();  // normal turns: 5 actions over 10 turns
  busy.turns[1] = turn(Speaker::kUser, 3, 3, 3, "URLLC", 90);  // 1 hard turn, 3 actions
  p = score_pillars(busy, kRelease, 10);
  const double r_h = 3.0, r_n = 5.0 / 9.0;
  EXPECT_DOUBLE_EQ(p.inputs.nr_adapt, std::clamp(1.5 - 0.5 * r_h / r_n, 0.0, 1.0));
  EXPECT_DOUBLE_EQ(p.inputs.nr_adapt, 0.0);  // 1.5 - 2.7 clamps to 0
  busy.turns[1].structured_actions = 1;  // r_h = 1 > r_n = 5/9
  EXPECT_DOUBLE_EQ(score_pillars(busy, kRelease, 10).inputs.nr_adapt, 1.5 - 0.5 * 1.0 / (5.0 / 9.0));

  // Actions only in hard turns: r_n = 0 gives adapt 0.
  EpisodeFacts only_hard = calm_episode();
  for (auto& t : only_hard.turns) t.structured_actions = 0;
  only_hard.turns[0] = turn(Speaker::kAgent, 2, 2, 2, "mMTC", 150);
  EXPECT_DOUBLE_EQ(score_pillars(only_hard, kRelease, 10).inputs.nr_adapt, 0.0);

  // All turns hard: N = 0, r_n = 0.
  EpisodeFacts all_hard = calm_episode();
  for (auto& t : all_hard.turns) t.lat_ms = 100;
  p = score_pillars(all_hard, kRelease, 10);
  EXPECT_EQ(p.inputs.hard_turns, 10);
  EXPECT_DOUBLE_EQ(p.inputs.nr_base, 0.5);
  EXPECT_DOUBLE_EQ(p.inputs.nr_adapt, 0.0);
  EXPECT_DOUBLE_EQ(p.nr, std::clamp(0.6 * 0.5 + 0.0 + 0.2 * 1.0 + 0.1, 0.0, 1.0));
}

TEST(Pillars, CommunicationCostUsesTheProfileBudgets) {
  EpisodeFacts e = calm_episode();
  e.total_tokens = 6000;  // 3000/6000 = 0.5
  for (int i = 0; i < 10; i += 2) e.turns[i].structured_actions = e.turns[i].matched_actions = 4;
  // 20 tools: 10/20 = 0.5
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).cc, 0.5);
  const ScoringProfile paper = paper_profile();
  // 10000/6000 clamps to 1; 25/20 clamps to 1.
  EXPECT_DOUBLE_EQ(score_pillars(e, paper, 10).cc, 1.0);
  e.total_tokens = 0;  // max(T_tok, 1)
  EXPECT_DOUBLE_EQ(score_pillars(e, kRelease, 10).cc, 0.5 * (1.0 + 0.5));
}

TEST(Pillars, Alpha3IsTheWeightedSum) {
  EpisodeFacts e = calm_episode();
  e.success = false;
  e.nfz_violation = true;
  e.total_tokens = 12000;
  const Pillars p = score_pillars(e, kRelease, 10);
  const PillarWeights w;
  EXPECT_NEAR(w.task_outcome + w.safety_policy + w.tool_consistency + w.interaction_quality +
                  w.network_robustness + w.communication_cost,
              1.0, 1e-15);
  EXPECT_DOUBLE_EQ(p.alpha3, 0.30 * p.to + 0.20 * p.sp + 0.20 * p.tc + 0.15 * p.iq +
                                 0.10 * p.nr + 0.05 * p.cc);
  EXPECT_DOUBLE_EQ(p.sp, 0.5);
  EXPECT_DOUBLE_EQ(p.cc, 0.5 * (0.25 + 1.0));
}

TEST(Profiles, ByNameAndUnknownName) {
  EXPECT_EQ(profile_by_name("release").token_budget, 3000.0);
  EXPECT_EQ(profile_by_name("paper").token_budget, 10000.0);
  EXPECT_EQ(profile_by_name("paper").tool_budget, 25.0);
  EXPECT_TRUE(profile_by_name("paper").optimal_turns_from_median);
  EXPECT_FALSE(profile_by_name("release").optimal_turns_from_median);
  try {
    profile_by_name("papers");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("papers"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("release"), std::string::npos);
  }
}

}  // namespace
}  // namespace a3::eval
