// The scenarios `a3rig generate` writes episodes for, from --scenarios arguments:
//   a folder          every sc-XXXX-ep-YY.json in it (a model's domain folder of the corpus,
//                     e.g. eval_runs/openai/chatgpt-4o-latest/uav): scenario XXXX is the
//                     initial_state of its lowest-numbered episode file
//   a .json file      an episode file (sc-XXXX-ep-YY.json: scenario XXXX) or a scenario file
//                     with "initial_state" (and optionally "mission.description")
//   a built-in name   a scenario of rigs/scenarios/ (nfz-detour, ...; rigs/scenario/scenario.hpp's
//                     builtin_scenario_names), with its mission
// Scenarios without a number from a file name get the next free numbers, in the order given.
#pragma once

#include <string>
#include <vector>

#include "rigs/generate/generate_prompt.hpp"

namespace a3::rigs {

// Sorted by number. Throws std::invalid_argument naming the argument (and file, and field) that
// is not a usable scenario, a folder without episode files, or a scenario number given twice.
std::vector<GenerateScenario> load_generate_scenarios(const std::vector<std::string>& specs);

}  // namespace a3::rigs
