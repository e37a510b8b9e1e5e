// The scenario format's JSON Schema (rigs/schema/scenario.schema.json, compiled in) and the
// checks every scenario document passes before anything is parsed or run: numbers finite,
// then the schema. A corpus initial_state (alphabench:<path>) is checked against the episode
// schema's `state` instead, the shape every public episode has.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace a3::rigs {

std::string_view scenario_schema_json();

// One line per problem: "<where>: <JSON path>: <reason>"; empty when the document passes.
// An initial_state's paths are written as in an episode ("/initial_state/uav/pose/x").
std::vector<std::string> scenario_schema_problems(const nlohmann::json& scenario, const std::string& where);
std::vector<std::string> corpus_initial_state_problems(const nlohmann::json& initial_state, const std::string& where);

// Throws common::InputError with every problem, one per line, when there is any.
void throw_if_problems(const std::vector<std::string>& problems);

}  // namespace a3::rigs
