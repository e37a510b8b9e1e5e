// JSON Schema validation of RapidJSON documents with valijson's verdicts (draft 7 semantics; our
// schemas use only keywords that mean the same in draft 2020-12). The schema is parsed once.
// is_valid() answers with the compiled schema (compiled_schema.hpp: no allocation, about ten
// times faster) when it supports every keyword the schema uses, else with valijson;
// violations() always explains a failure with valijson.
#pragma once

#include "eval/rapidjson.hpp"

#include <memory>
#include <string>
#include <string_view>

#include "eval/compiled_schema.hpp"
#include "eval/violation.hpp"

namespace valijson {
class Schema;
}

namespace a3::eval {

// Who answers is_valid().
enum class SchemaEngine {
  kCompiledWhenSupported,  // the compiled schema, or valijson when it refuses a keyword
  kCompiled,               // the compiled schema; construction throws when it refuses a keyword
  kValijson,               // valijson only (the reference the compiled schema is tested against)
};

class JsonSchemaValidator {
 public:
  // schema_json: the schema text. Throws std::invalid_argument naming `schema_name` when
  // the text is not JSON or not a schema valijson can use (or, with kCompiled, compile).
  JsonSchemaValidator(std::string_view schema_json, std::string_view schema_name,
                      SchemaEngine engine = SchemaEngine::kCompiledWhenSupported);
  ~JsonSchemaValidator();
  JsonSchemaValidator(const JsonSchemaValidator&) = delete;
  JsonSchemaValidator& operator=(const JsonSchemaValidator&) = delete;

  // Thread-safe: the parsed schema is only read.
  bool is_valid(const rapidjson::Value& document) const;
  // valijson's verdict, whatever the engine.
  bool valijson_is_valid(const rapidjson::Value& document) const;
  // The leaf-most failures (rule "schema"), each with the JSON Pointer of the bad value.
  Violations violations(const rapidjson::Value& document) const;

  bool uses_compiled_schema() const { return compiled_ != nullptr; }
  // Why the compiled schema is not used (empty when it is, or when valijson was asked for).
  const std::string& compiled_schema_refusal() const { return refusal_; }

 private:
  std::unique_ptr<valijson::Schema> schema_;
  std::unique_ptr<CompiledSchema> compiled_;
  std::string refusal_;
};

// valijson's error context (["<root>", "[dialogue]", "[3]", "[speaker]"]) as a JSON Pointer
// ("/dialogue/3/speaker").
std::string context_to_json_pointer(const std::vector<std::string>& context);

}  // namespace a3::eval
