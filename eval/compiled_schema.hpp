// A JSON Schema compiled once into a list of subschemas whose keyword checks walk a RapidJSON
// value without allocating: the yes/no answer of scoring's schema validation. The verdict is
// exactly valijson's (draft 7, strong types: see valijson_values.hpp for its quirks) for the
// keywords supported, which are those eval/schema/episode.schema.json uses: type, required,
// properties, additionalProperties, items (one schema), minItems, maxItems, minimum, maximum,
// multipleOf (non-integer divisor), const, enum, if/then/else, $ref to "#/…" without sibling
// keywords, $defs, boolean schemas, and the annotations $schema, title, description, $comment.
// Any other keyword or form is refused at construction with its JSON Pointer, so a schema change
// can never be validated more weakly than written. Differential tests against valijson:
// tests/eval/test_compiled_schema*.cpp.
#pragma once

#include "eval/rapidjson.hpp"

#include <string_view>
#include <vector>

#include "eval/schema_node.hpp"

namespace a3::eval {

class CompiledSchema {
 public:
  // Throws std::invalid_argument naming `schema_name`, and the keyword and its JSON Pointer when
  // the schema uses something not supported.
  CompiledSchema(std::string_view schema_json, std::string_view schema_name);
  CompiledSchema(const CompiledSchema&) = delete;
  CompiledSchema& operator=(const CompiledSchema&) = delete;

  // Thread-safe (only reads). Recursion follows the value's depth: bound it first (json_shape).
  bool is_valid(const rapidjson::Value& value) const { return valid_at(root_, value); }

  std::size_t subschema_count() const { return nodes_.size(); }

 private:
  friend class SchemaCompiler;
  bool valid_at(SchemaNodeIndex node, const rapidjson::Value& value) const;
  bool object_valid(const SchemaNode& node, const rapidjson::Value& object) const;
  bool array_valid(const SchemaNode& node, const rapidjson::Value& array) const;
  bool additional_valid(const SchemaNode& node, const rapidjson::Value& object) const;
  bool conditional_valid(const SchemaNode& node, const rapidjson::Value& value) const;

  rapidjson::Document schema_;  // const and enum values point into it
  std::vector<SchemaNode> nodes_;
  SchemaNodeIndex root_ = kNoSchemaNode;
};

}  // namespace a3::eval
