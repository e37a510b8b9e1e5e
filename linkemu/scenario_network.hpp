// The scenario's `network` section (docs/scenarios.md): the initial slice, scripted windows of
// forced degradation, a recorded trace to replay, and `link`, the link emulator's own settings
// (link_emulator_config.hpp). Parsed here, once, into a typed ScenarioNetwork; the orchestrator
// applies the run's seed and --slice over it.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "linkemu/link_emulator_config.hpp"

namespace a3::linkemu {

struct ScenarioNetwork {
  std::string initial_slice = "eMBB";  // URLLC, eMBB or mMTC
  // Windows of forced degradation (the SPEC §2 hard regime), mission seconds.
  struct Window {
    double start_s = 0.0;
    double duration_s = 0.0;
  };
  std::vector<Window> degradations;
  // A recorded trace to replay instead of the seeded process: a file (made absolute against the
  // scenario's folder) or alphabench:<path> (resolved by the orchestrator against the shared folder).
  std::string trace;
  double trace_period_s = 20.0;
  // network.link: the link emulator's own settings, without seed, slice, trace and
  // degradations (the run's --seed and the fields above set those).
  LinkEmulatorConfig link;
};

// Parses a network object; `json_path` names it ("file.json: /network"), `base_dir` is the
// scenario's folder. Throws common::InputError naming the path of the bad field
// ("file.json: /network/initial_slice: 'LTE' is not URLLC, eMBB or mMTC").
ScenarioNetwork parse_scenario_network(const nlohmann::json& network, const std::string& json_path,
                                       const std::filesystem::path& base_dir);

}  // namespace a3::linkemu
