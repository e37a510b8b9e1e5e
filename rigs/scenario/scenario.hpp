// A scenario: an α³-Bench initial_state (the corpus format), a mission (the objectives that
// decide success), airspace extras the corpus lacks (no-fly zones, other traffic), the
// airframe, and the network script. Loaded from JSON (rigs/scenarios/*.json are built in;
// the format is docs/scenarios.md, its schema rigs/schema/scenario.schema.json): checked
// against the schema, parsed once into typed sections, then checked for sense (home and
// objectives inside the geofence and clear of no-fly zones, wind and payload within the
// airframe's limits), every error naming the file and JSON path; or derived from any
// initial_state of the public corpus (`alphabench:<path>`).
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "agent/airspace.hpp"
#include "agent/mission/mission.hpp"
#include "linkemu/scenario_network.hpp"
#include "rigs/scenario/initial_state.hpp"

namespace a3::rigs {

struct Scenario {
  std::string name;
  std::string description;
  std::string source;  // where it was loaded from
  std::string airframe = "iris";
  nlohmann::json initial_state;  // as given: the episode's initial_state is written from it
  InitialState start;            // the same, parsed: what every node is configured from
  agent::Mission mission;
  agent::Airspace airspace;
  linkemu::ScenarioNetwork network;  // parsed by linkemu::parse_scenario_network

  // What agents are told about the airspace: geofence, altitude envelope, no-fly zones, and
  // the other aircraft (ids and declared intent, not their future).
  nlohmann::json airspace_brief() const;
};

// Throws common::InputError naming `where` and the JSON path, one line per problem.
Scenario scenario_from_json(const nlohmann::json& j, const std::string& where,
                            const std::filesystem::path& base_dir);
// A name of a built-in scenario, a JSON file, or alphabench:<path> (relative to the shared
// folder's alphabench/eval_runs, or absolute). Generated missions (gen:...) are made before
// loading: rigs/generator/scenario_spec.hpp's load_scenario_spec takes every kind.
Scenario load_scenario(const std::string& spec, const std::filesystem::path& shared_dir);
std::vector<std::string> builtin_scenario_names();
// The document of a built-in scenario, nullopt for a name that is not one.
std::optional<nlohmann::json> builtin_scenario_json(const std::string& name);

// A default mission for a corpus initial_state: take off from below its pose, image a point
// up to 250 m away toward the geofence's centre, and return and land. The state is checked
// against the episode schema's `state` (the public corpus' shapes: a moving start, extra
// payload fields) and then by the same parser and rules as a scenario file; `where` names
// the document, errors name paths as in an episode (/initial_state/...).
Scenario scenario_from_initial_state(const nlohmann::json& initial_state, const std::string& where);

}  // namespace a3::rigs
