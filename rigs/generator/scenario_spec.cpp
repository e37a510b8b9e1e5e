// gen: specs first, then the loader.
#include "rigs/generator/scenario_spec.hpp"

#include "rigs/generator/scenario_generator.hpp"
#include "rigs/generator/scenario_generator_knobs.hpp"

namespace a3::rigs {

Scenario load_scenario_spec(const std::string& spec, const std::filesystem::path& shared_dir) {
  if (is_generator_spec(spec)) return generate_scenario(spec);
  return load_scenario(spec, shared_dir);
}

}  // namespace a3::rigs
