// The six α³ pillars of one valid episode and the composite α³ (SPEC-alpha3.md §2), with the
// intermediate quantities a per-episode report shows.
#pragma once

#include "eval/episode_facts.hpp"
#include "eval/scoring_profile.hpp"

namespace a3::eval {

struct PillarInputs {
  int turns = 0;                 // T
  int agent_turns = 0;
  int agent_turns_with_obs = 0;  // numerator of G
  bool alternation_ok = false;   // A_alt
  int structured_actions = 0;    // T_tool, and the denominator of TC
  int matched_actions = 0;
  int hard_turns = 0;            // H
  int hard_actions = 0;          // C_h
  int normal_actions = 0;        // C_n
  int hard_penalised_slice_turns = 0;  // hard turns on eMBB
  bool v_alt = false, v_nfz = false, v_sep = false, v_batt = false;
  bool landed_at_home = false;   // the rig's landing marker, checked: not an altitude violation
  double optimal_turns = 0.0;    // T_opt used
  double total_tokens = 0.0;     // T_tok
  // NR terms
  double nr_base = 0.0, nr_adapt = 0.0, nr_slice = 0.0, nr_bonus = 0.0;
};

struct Pillars {
  double to = 0.0, sp = 0.0, tc = 0.0, iq = 0.0, nr = 0.0, cc = 0.0;
  double alpha3 = 0.0;
  PillarInputs inputs;
};

// A landed vehicle is on the ground, not flying below the altitude envelope. The rig marks a
// landing at home (final_state.uav.landed.site = "home"); the marker counts only when the final
// pose agrees: near the ground and near the initial pose (where the vehicle took off), within
// the profile's landed_* limits.
bool landed_at_home(const EpisodeFacts& episode, const SafetyPenalties& safety);

bool is_hard_turn(const TurnFacts& turn, const HardTurnThresholds& hard);

Pillars score_pillars(const EpisodeFacts& episode, const ScoringProfile& profile,
                      double optimal_turns);

double clamp01(double x);

}  // namespace a3::eval
