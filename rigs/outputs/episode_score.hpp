// One episode scored as `a3rig score` scores it (schema, semantic rules, the release profile's
// pillars), for a run's closing lines and its report.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "eval/pillars.hpp"

namespace a3::rigs {

struct EpisodeScore {
  bool valid = false;
  eval::Pillars pillars;                // valid episodes only
  std::vector<std::string> violations;  // why it is not valid ("<JSON path>: <rule>: <message>")
};

EpisodeScore score_episode(const nlohmann::json& episode);

// {"valid", "alpha3", "pillars": {"TO", "SP", "TC", "IQ", "NR", "CC"}, "inputs": {...}, "violations"}.
nlohmann::json episode_score_json(const EpisodeScore& score);

}  // namespace a3::rigs
