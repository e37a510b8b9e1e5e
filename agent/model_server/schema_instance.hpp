// A JSON value made to satisfy a JSON Schema, for answers the responder has no content for: the
// arguments of a tool call a generic client asked for, or a response_format json_schema reply.
// Rules: const, else the first enum value, else by type (the first non-null of a type list):
// objects get their required properties (OpenAI's strict mode lists them all); numbers within
// minimum/maximum
// (exclusive bounds respected; multipleOf honoured); strings of at least minLength; arrays of
// minItems items; anyOf/oneOf take the first branch, allOf merges its branches; local $ref
// ("#/$defs/X", "#/definitions/X") is followed. Values are deterministic.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace a3::agent::model_server {

nlohmann::json instance_of_schema(const nlohmann::json& schema);

// "" when `value` satisfies `schema` (draft 7, valijson), else the problems.
std::string schema_problems(const nlohmann::json& schema, const nlohmann::json& value);

}  // namespace a3::agent::model_server
