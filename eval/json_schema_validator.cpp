// valijson behind a small interface.
#include "eval/json_schema_validator.hpp"

#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include <algorithm>
#include <stdexcept>

#include "common/json_pointer.hpp"

namespace a3::eval {

JsonSchemaValidator::JsonSchemaValidator(std::string_view schema_json,
                                         std::string_view schema_name, SchemaEngine engine)
    : schema_(std::make_unique<valijson::Schema>()) {
  rapidjson::Document doc;
  doc.Parse(schema_json.data(), schema_json.size());
  if (doc.HasParseError()) {
    throw std::invalid_argument(std::string(schema_name) + ": schema is not valid JSON (offset " +
                                std::to_string(doc.GetErrorOffset()) + "): " +
                                rapidjson::GetParseError_En(doc.GetParseError()));
  }
  try {
    valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
    valijson::adapters::RapidJsonAdapter adapter(doc);
    parser.populateSchema(adapter, *schema_);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string(schema_name) + ": not a usable JSON Schema: " +
                                e.what());
  }
  if (engine == SchemaEngine::kValijson) return;
  try {
    compiled_ = std::make_unique<CompiledSchema>(schema_json, schema_name);
  } catch (const std::invalid_argument& e) {
    if (engine == SchemaEngine::kCompiled) throw;
    refusal_ = e.what();
  }
}

JsonSchemaValidator::~JsonSchemaValidator() = default;

bool JsonSchemaValidator::is_valid(const rapidjson::Value& document) const {
  return compiled_ ? compiled_->is_valid(document) : valijson_is_valid(document);
}

bool JsonSchemaValidator::valijson_is_valid(const rapidjson::Value& document) const {
  valijson::Validator validator;
  valijson::adapters::RapidJsonAdapter adapter(document);
  return validator.validate(*schema_, adapter, nullptr);
}

std::string context_to_json_pointer(const std::vector<std::string>& context) {
  std::string pointer;
  for (const std::string& part : context) {
    if (part == "<root>") continue;
    std::string_view token = part;
    if (token.size() >= 2 && token.front() == '[' && token.back() == ']') {
      token = token.substr(1, token.size() - 2);
    }
    pointer += '/';
    pointer += common::json_pointer_token(token);
  }
  return pointer;
}

Violations JsonSchemaValidator::violations(const rapidjson::Value& document) const {
  valijson::Validator validator;
  valijson::ValidationResults results;
  valijson::adapters::RapidJsonAdapter adapter(document);
  if (validator.validate(*schema_, adapter, &results)) return {};

  std::vector<std::pair<std::string, std::string>> errors;
  valijson::ValidationResults::Error error;
  while (results.popError(error)) {
    errors.emplace_back(context_to_json_pointer(error.context), error.description);
  }
  // valijson also reports every enclosing object and array ("Failed to validate item #3 in
  // array.", "... associated with property name 'dialogue'."): report the specific errors,
  // and fall back to the deepest summaries only when there is nothing more specific.
  auto is_summary = [](const std::string& description) {
    return description.rfind("Failed to validate ", 0) == 0;
  };
  auto has_deeper = [&](const std::string& pointer) {
    return std::any_of(errors.begin(), errors.end(), [&](const auto& other) {
      return other.first.size() > pointer.size() &&
             other.first.compare(0, pointer.size(), pointer) == 0 && other.first[pointer.size()] == '/';
    });
  };
  const bool any_specific = std::any_of(errors.begin(), errors.end(),
                                        [&](const auto& e) { return !is_summary(e.second); });
  Violations out;
  for (const auto& error : errors) {
    // Named copies, not structured bindings: clang 14 (the fuzz build) cannot capture those.
    const std::string& pointer = error.first;
    const std::string& description = error.second;
    if (any_specific ? is_summary(description) : has_deeper(pointer)) continue;
    const bool duplicate = std::any_of(out.begin(), out.end(), [&](const Violation& v) {
      return v.json_path == pointer && v.message == description;
    });
    if (!duplicate) out.push_back({pointer, "schema", description});
  }
  return out;
}

}  // namespace a3::eval
