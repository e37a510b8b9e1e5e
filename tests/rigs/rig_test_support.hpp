// Running whole episodes from tests.
#pragma once

#include <filesystem>
#include <string>

#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/pillars.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/run/rig_runner.hpp"
#include "tests/eval/episode_builder.hpp"
#include "tests/test_support.hpp"

namespace a3::test {

inline rigs::RunOptions virtual_run(const std::string& scenario, const std::string& out_tag) {
  rigs::RunOptions o;
  o.scenario = scenario;
  o.runtime = rigs::Runtime::kVirtual;
  o.out_dir = std::filesystem::temp_directory_path() / ("a3rig-test-rig-" + out_tag + "-" + std::to_string(::getpid()));
  o.write_lcm_log = false;
  o.write_plot = false;
  o.write_report = false;
  o.quiet = true;
  o.shared_dir = shared_dir();
  return o;
}

inline rigs::RunResult run(const rigs::RunOptions& o) {
  const rigs::Scenario s = rigs::load_scenario_spec(o.scenario, o.shared_dir);
  return rigs::run_episode(s, o, {}, nullptr);
}

struct Scored {
  bool valid = false;
  std::string problems;
  eval::Pillars pillars;
};

inline Scored score(const nlohmann::json& episode) {
  static const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  const eval::ScoringProfile profile = eval::release_profile();
  eval::EpisodeReader reader(validator, profile);
  const eval::EpisodeCheck check = reader.check_text(episode.dump());
  Scored out;
  out.valid = check.status == eval::EpisodeStatus::kValid;
  for (const auto& v : check.violations) out.problems += eval::to_string(v) + "\n";
  if (out.valid) out.pillars = eval::score_pillars(check.facts, profile, profile.optimal_turns);
  return out;
}

}  // namespace a3::test
