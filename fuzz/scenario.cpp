// Fuzz target "scenario": a scenario file's text as `a3rig run --scenario FILE` reads it
// (bounded JSON parsing, then every section checked field by field), and what agents are told
// of a scenario that loads; and the same text as the tail of a generated-mission spec
// (gen:<text>), parsed without generating. Bad input must be an InputError naming the field,
// nothing else; a spec that parses prints as text that parses to the same spec.
#include <string_view>

#include "common/json_file.hpp"
#include "common/json_text.hpp"
#include "fuzz/fuzz_target.hpp"
#include "rigs/generator/scenario_generator_knobs.hpp"
#include "rigs/scenario/scenario.hpp"

namespace {

void load_scenario_text(std::string_view text) {
  try {
    const nlohmann::json j = a3::common::parse_json_text(text, "fuzz.json");
    const a3::rigs::Scenario scenario = a3::rigs::scenario_from_json(j, "fuzz.json", ".");
    (void)a3::common::dump_json_text(scenario.airspace_brief());
  } catch (const a3::common::InputError&) {
  }
}

void parse_generator_spec_text(std::string_view text) {
  const std::string spec = "gen:" + std::string(text);
  try {
    const std::string printed = a3::rigs::generator_spec_text(a3::rigs::parse_generator_spec(spec));
    a3::fuzz::require(a3::rigs::generator_spec_text(a3::rigs::parse_generator_spec(printed)) == printed,
                      "a generator spec does not print as text that parses to the same spec");
  } catch (const a3::common::InputError&) {
  }
}

}  // namespace

A3_FUZZ_TARGET(scenario) {
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  load_scenario_text(text);
  parse_generator_spec_text(text);
}
