// A scenario as the command line names it: a generated mission (gen:SEED[:knobs], made here
// before anything is loaded), else what rigs/scenario's load_scenario reads (a built-in name, a
// JSON file, alphabench:<path>). The scenario loader itself never generates.
#pragma once

#include <filesystem>
#include <string>

#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

// Throws common::InputError naming the spec and what is wrong with it.
Scenario load_scenario_spec(const std::string& spec, const std::filesystem::path& shared_dir);

}  // namespace a3::rigs
