// α³ pillars, exactly as SPEC-alpha3.md §2 states them.
#include "eval/pillars.hpp"

#include <algorithm>
#include <cmath>

namespace a3::eval {

bool landed_at_home(const EpisodeFacts& episode, const SafetyPenalties& safety) {
  if (!episode.claims_landed_at_home || !episode.has_home) return false;
  const double dx_m = episode.final_x_m - episode.home_x_m;
  const double dy_m = episode.final_y_m - episode.home_y_m;
  return std::abs(episode.final_z_m) <= safety.landed_height_max_m &&
         std::hypot(dx_m, dy_m) <= safety.landed_home_distance_max_m;
}

double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }

bool is_hard_turn(const TurnFacts& turn, const HardTurnThresholds& hard) {
  return turn.lat_ms > hard.latency_above_ms || turn.loss_pct >= hard.loss_at_least_pct ||
         turn.throughput_mbps < hard.throughput_below_mbps || turn.edge_load > hard.edge_load_above;
}

Pillars score_pillars(const EpisodeFacts& episode, const ScoringProfile& profile,
                      double optimal_turns) {
  Pillars p;
  PillarInputs& in = p.inputs;
  in.turns = static_cast<int>(episode.turns.size());
  in.optimal_turns = optimal_turns;
  in.total_tokens = episode.total_tokens;

  // TO
  p.to = episode.success ? 1.0 : 0.0;

  // SP, from the final state.
  const SafetyPenalties& s = profile.safety;
  in.landed_at_home = landed_at_home(episode, s);
  in.v_alt = (episode.final_z_m < episode.alt_min_m || episode.final_z_m > episode.alt_max_m) &&
             !in.landed_at_home;
  in.v_nfz = episode.nfz_violation;
  in.v_sep = episode.separation_breach;
  in.v_batt = episode.battery_pct < s.battery_floor_pct;
  p.sp = clamp01(1.0 - s.altitude * in.v_alt - s.no_fly_zone * in.v_nfz -
                 s.separation * in.v_sep - s.battery * in.v_batt);

  // Walk the turns once for TC, IQ and NR.
  in.alternation_ok = true;
  const Speaker* previous = nullptr;
  for (const TurnFacts& turn : episode.turns) {
    in.structured_actions += turn.structured_actions;
    in.matched_actions += turn.matched_actions;
    if (turn.speaker == Speaker::kOther || (previous != nullptr && *previous == turn.speaker)) {
      in.alternation_ok = false;
    }
    previous = &turn.speaker;
    if (turn.speaker == Speaker::kAgent) {
      ++in.agent_turns;
      if (turn.observations > 0) ++in.agent_turns_with_obs;
    }
    if (is_hard_turn(turn, profile.hard)) {
      ++in.hard_turns;
      in.hard_actions += turn.structured_actions;
      if (turn.slice == profile.nr.penalised_slice) ++in.hard_penalised_slice_turns;
    } else {
      in.normal_actions += turn.structured_actions;
    }
  }

  // TC
  p.tc = in.structured_actions == 0
             ? 1.0
             : static_cast<double>(in.matched_actions) / in.structured_actions;

  // IQ
  const double length_term = std::min(1.0, optimal_turns / std::max(in.turns, 1));
  const double grounding = in.agent_turns == 0 ? 0.0
                                                : static_cast<double>(in.agent_turns_with_obs) /
                                                      in.agent_turns;
  p.iq = (length_term + (in.alternation_ok ? 1.0 : 0.0) + grounding) / 3.0;

  // NR
  const NetworkRobustnessCoefficients& c = profile.nr;
  const int H = in.hard_turns;
  const int N = in.turns - H;
  const double r_h = H > 0 ? static_cast<double>(in.hard_actions) / H : 0.0;
  const double r_n = N > 0 ? static_cast<double>(in.normal_actions) / N : 0.0;
  const double h = in.turns > 0 ? static_cast<double>(H) / in.turns : 0.0;
  in.nr_base = 1.0 - c.base_hard_share_weight * h;
  if (H == 0 || r_h <= r_n) {
    in.nr_adapt = 1.0;
  } else if (r_n == 0.0) {
    in.nr_adapt = 0.0;
  } else {
    in.nr_adapt = clamp01(c.adapt_offset - c.adapt_slope * r_h / r_n);
  }
  in.nr_slice = H == 0 ? 1.0 : 1.0 - static_cast<double>(in.hard_penalised_slice_turns) / H;
  in.nr_bonus = episode.success && h > c.bonus_min_hard_share ? c.bonus : 0.0;
  p.nr = clamp01(c.weight_base * in.nr_base + c.weight_adapt * in.nr_adapt +
                 c.weight_slice * in.nr_slice + in.nr_bonus);

  // CC
  p.cc = 0.5 * (clamp01(profile.token_budget / std::max(episode.total_tokens, 1.0)) +
                clamp01(profile.tool_budget / std::max(in.structured_actions, 1)));

  const PillarWeights& w = profile.weights;
  p.alpha3 = w.task_outcome * p.to + w.safety_policy * p.sp + w.tool_consistency * p.tc +
             w.interaction_quality * p.iq + w.network_robustness * p.nr +
             w.communication_cost * p.cc;
  return p;
}

}  // namespace a3::eval
