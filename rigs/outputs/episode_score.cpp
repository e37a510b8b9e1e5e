// Scoring one episode document with the release profile.
#include "rigs/outputs/episode_score.hpp"

#include "common/json_text.hpp"
#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/json_schema_validator.hpp"

namespace a3::rigs {

EpisodeScore score_episode(const nlohmann::json& episode) {
  const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  const eval::ScoringProfile profile = eval::release_profile();
  eval::EpisodeReader reader(validator, profile);
  const eval::EpisodeCheck check = reader.check_text(common::dump_json_text(episode));
  EpisodeScore out;
  out.valid = check.status == eval::EpisodeStatus::kValid;
  if (out.valid) out.pillars = eval::score_pillars(check.facts, profile, profile.optimal_turns);
  for (const auto& v : check.violations) out.violations.push_back(eval::to_string(v));
  return out;
}

nlohmann::json episode_score_json(const EpisodeScore& score) {
  const eval::Pillars& p = score.pillars;
  const eval::PillarInputs& in = p.inputs;
  nlohmann::json out = {{"valid", score.valid}, {"violations", score.violations}};
  if (!score.valid) return out;
  out["alpha3"] = p.alpha3;
  out["pillars"] = {{"TO", p.to}, {"SP", p.sp}, {"TC", p.tc}, {"IQ", p.iq}, {"NR", p.nr}, {"CC", p.cc}};
  out["inputs"] = {{"turns", in.turns},
                   {"agent_turns", in.agent_turns},
                   {"agent_turns_with_obs", in.agent_turns_with_obs},
                   {"alternation_ok", in.alternation_ok},
                   {"structured_actions", in.structured_actions},
                   {"matched_actions", in.matched_actions},
                   {"hard_turns", in.hard_turns},
                   {"altitude_violation", in.v_alt},
                   {"nfz_violation", in.v_nfz},
                   {"separation_violation", in.v_sep},
                   {"battery_violation", in.v_batt},
                   {"landed_at_home", in.landed_at_home},
                   {"optimal_turns", in.optimal_turns},
                   {"total_tokens", in.total_tokens}};
  return out;
}

}  // namespace a3::rigs
