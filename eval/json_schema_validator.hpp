// JSON Schema validation of RapidJSON documents with valijson (draft 7 semantics; our schemas
// use only keywords that mean the same in draft 2020-12). The schema is parsed once; is_valid()
// stops at the first failure (the fast path), violations() explains a failure.
#pragma once

#include "eval/rapidjson.hpp"

#include <memory>
#include <string>
#include <string_view>

#include "eval/violation.hpp"

namespace valijson {
class Schema;
}

namespace a3::eval {

class JsonSchemaValidator {
 public:
  // schema_json: the schema text. Throws std::invalid_argument naming `schema_name` when
  // the text is not JSON or not a schema valijson can use.
  JsonSchemaValidator(std::string_view schema_json, std::string_view schema_name);
  ~JsonSchemaValidator();
  JsonSchemaValidator(const JsonSchemaValidator&) = delete;
  JsonSchemaValidator& operator=(const JsonSchemaValidator&) = delete;

  // Thread-safe: the parsed schema is only read.
  bool is_valid(const rapidjson::Value& document) const;
  // The leaf-most failures (rule "schema"), each with the JSON Pointer of the bad value.
  Violations violations(const rapidjson::Value& document) const;

 private:
  std::unique_ptr<valijson::Schema> schema_;
};

// valijson's error context (["<root>", "[dialogue]", "[3]", "[speaker]"]) as a JSON Pointer
// ("/dialogue/3/speaker").
std::string context_to_json_pointer(const std::vector<std::string>& context);

}  // namespace a3::eval
