// Fuzz target "scenario": a scenario file's text as `a3rig run --scenario FILE` reads it
// (bounded JSON parsing, then every section checked field by field), and what agents are told
// of a scenario that loads. Bad input must be an InputError naming the field, nothing else.
#include <string_view>

#include "common/json_file.hpp"
#include "common/json_text.hpp"
#include "fuzz/fuzz_target.hpp"
#include "rigs/core/scenario.hpp"

A3_FUZZ_TARGET(scenario) {
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  try {
    const nlohmann::json j = a3::common::parse_json_text(text, "fuzz.json");
    const a3::rigs::Scenario scenario = a3::rigs::scenario_from_json(j, "fuzz.json", ".");
    (void)a3::common::dump_json_text(scenario.airspace_brief());
  } catch (const a3::common::InputError&) {
  }
}
