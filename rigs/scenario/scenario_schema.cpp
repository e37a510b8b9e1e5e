// Scenario documents against their schemas, with valijson (through eval's validator).
#include "rigs/scenario/scenario_schema.hpp"

#include <cmath>

#include "common/json_file.hpp"
#include "common/json_pointer.hpp"
#include "eval/episode_schema.hpp"
#include "eval/json_schema_validator.hpp"

namespace a3::rigs {
namespace {

// A number too large for a double parses as infinity; JSON has no other non-finite numbers.
void collect_non_finite(const nlohmann::json& j, const std::string& pointer, const std::string& where,
                        std::vector<std::string>& out) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) {
    out.push_back(where + ": " + (pointer.empty() ? "/" : pointer) + ": not a finite number");
  } else if (j.is_object()) {
    for (const auto& [key, value] : j.items()) collect_non_finite(value, pointer + "/" + common::json_pointer_token(key), where, out);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) collect_non_finite(j[i], pointer + "/" + std::to_string(i), where, out);
  }
}

std::vector<std::string> schema_problems(const eval::JsonSchemaValidator& validator, const nlohmann::json& document,
                                         const std::string& where, const std::string& pointer_prefix) {
  std::vector<std::string> out;
  collect_non_finite(document, pointer_prefix, where, out);
  if (!out.empty()) return out;
  const std::string text = document.dump();
  rapidjson::Document doc;
  doc.Parse(text.data(), text.size());
  for (const auto& v : validator.violations(doc)) {
    const std::string pointer = pointer_prefix + v.json_path;
    out.push_back(where + ": " + (pointer.empty() ? "/" : pointer) + ": " + v.message);
  }
  return out;
}

// The episode schema with its root replaced by a reference to its `state` definition.
std::string corpus_state_schema() {
  nlohmann::json schema = nlohmann::json::parse(eval::episode_schema_json());
  nlohmann::json out = {{"$schema", schema["$schema"]}, {"$ref", "#/$defs/state"}, {"$defs", schema["$defs"]}};
  return out.dump();
}

}  // namespace

std::vector<std::string> scenario_schema_problems(const nlohmann::json& scenario, const std::string& where) {
  static const eval::JsonSchemaValidator validator(scenario_schema_json(), "rigs/schema/scenario.schema.json");
  return schema_problems(validator, scenario, where, "");
}

std::vector<std::string> corpus_initial_state_problems(const nlohmann::json& initial_state, const std::string& where) {
  static const eval::JsonSchemaValidator validator(corpus_state_schema(), "eval/schema/episode.schema.json#/$defs/state");
  return schema_problems(validator, initial_state, where, "/initial_state");
}

void throw_if_problems(const std::vector<std::string>& problems) {
  if (problems.empty()) return;
  std::string text;
  for (const auto& p : problems) text += (text.empty() ? "" : "\n") + p;
  throw common::InputError(text);
}

}  // namespace a3::rigs
