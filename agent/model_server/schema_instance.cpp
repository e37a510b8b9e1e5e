// Generating and checking instances of a JSON Schema.
#include "agent/model_server/schema_instance.hpp"

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace a3::agent::model_server {
namespace {

using nlohmann::json;
constexpr int kMaxDepth = 16;  // recursive schemas ($ref to itself) stop here
// A tool schema comes from the client: an instance holds at most this many array items and
// string characters, whatever minItems / minLength ask (the instance then fails validation,
// which is reported, instead of exhausting memory).
constexpr std::size_t kMaxInstanceItems = 64;
constexpr std::size_t kMaxInstanceStringBytes = 4096;
// Integers stay where a double still counts exactly.
constexpr double kMaxInstanceInteger = 9007199254740992.0;  // 2^53

json instance(const json& schema, const json& root, int depth);

const json* resolve_ref(const std::string& ref, const json& root) {
  if (ref.rfind("#", 0) != 0) return nullptr;
  try {
    const json::json_pointer pointer(ref.substr(1));
    return root.contains(pointer) ? &root.at(pointer) : nullptr;
  } catch (const json::exception&) {
    return nullptr;
  }
}

// A count keyword (minItems, minLength) capped at `cap`; 0 when absent or not a count.
std::size_t count_keyword(const json& s, const char* key, std::size_t cap) {
  const auto it = s.find(key);
  if (it == s.end() || !it->is_number_unsigned()) return 0;
  return static_cast<std::size_t>(std::min<uint64_t>(it->get<uint64_t>(), cap));
}

std::string string_keyword(const json& s, const char* key) {
  const auto it = s.find(key);
  return it != s.end() && it->is_string() ? it->get<std::string>() : std::string();
}

std::string type_of(const json& schema) {
  const auto t = schema.find("type");
  if (t == schema.end()) {
    if (schema.contains("properties") || schema.contains("required")) return "object";
    if (schema.contains("items")) return "array";
    return "";
  }
  if (t->is_string()) return t->get<std::string>();
  if (t->is_array()) {
    for (const auto& x : *t) {
      if (x.is_string() && x != "null") return x.get<std::string>();
    }
    if (!t->empty()) return "null";
  }
  return "";
}

double number_in_bounds(const json& s, bool integer) {
  double lo = -INFINITY, hi = INFINITY;
  const double step = integer ? 1.0 : 0.5;
  if (s.contains("minimum") && s["minimum"].is_number()) lo = s["minimum"].get<double>();
  if (s.contains("exclusiveMinimum") && s["exclusiveMinimum"].is_number()) lo = s["exclusiveMinimum"].get<double>() + step;
  if (s.contains("maximum") && s["maximum"].is_number()) hi = s["maximum"].get<double>();
  if (s.contains("exclusiveMaximum") && s["exclusiveMaximum"].is_number()) hi = s["exclusiveMaximum"].get<double>() - step;
  double x = std::isfinite(lo) ? lo : (std::isfinite(hi) ? std::min(0.0, hi) : 0.0);
  if (integer) x = std::ceil(x);
  if (s.contains("multipleOf") && s["multipleOf"].is_number() && s["multipleOf"].get<double>() > 0) {
    const double m = s["multipleOf"].get<double>();
    x = std::ceil(x / m) * m;
  }
  if (x > hi && std::isfinite(lo)) x = (lo + hi) / 2.0;
  return x;
}

json object_instance(const json& s, const json& root, int depth) {
  json out = json::object();
  const json properties = s.value("properties", json::object());
  for (const auto& name : s.value("required", json::array())) {
    if (!name.is_string()) continue;
    const std::string key = name.get<std::string>();
    out[key] = properties.contains(key) ? instance(properties[key], root, depth + 1) : json("");
  }
  return out;
}

json array_instance(const json& s, const json& root, int depth) {
  json out = json::array();
  const std::size_t n = count_keyword(s, "minItems", kMaxInstanceItems);
  const json items = s.contains("items") && s["items"].is_object() ? s["items"] : json::object();
  for (std::size_t i = 0; i < n; ++i) out.push_back(instance(items, root, depth + 1));
  return out;
}

json string_instance(const json& s) {
  std::string text = "a3rig";
  const std::size_t min_length = count_keyword(s, "minLength", kMaxInstanceStringBytes);
  if (text.size() < min_length) text.append(min_length - text.size(), 'x');
  if (s.contains("maxLength") && s["maxLength"].is_number_unsigned()) text.resize(std::min(text.size(), s["maxLength"].get<std::size_t>()));
  const std::string format = string_keyword(s, "format");
  if (format == "date-time") return "2026-01-01T00:00:00Z";
  if (format == "date") return "2026-01-01";
  if (format == "email") return "a3rig@example.com";
  if (format == "uri") return "https://example.com/a3rig";
  if (format == "uuid") return "00000000-0000-4000-8000-000000000000";
  return text;
}

json merged_all_of(const json& s, const json& root) {
  json merged = s;
  merged.erase("allOf");
  for (const auto& branch : s["allOf"]) {
    const std::string ref = branch.is_object() ? string_keyword(branch, "$ref") : std::string();
    const json* b = ref.empty() ? &branch : resolve_ref(ref, root);
    if (b == nullptr || !b->is_object()) continue;
    for (const auto& [key, value] : b->items()) {
      if (key == "properties" && merged.contains("properties") && merged["properties"].is_object() &&
          value.is_object()) {
        merged["properties"].update(value);
      } else if (key == "required" && merged.contains("required") && merged["required"].is_array() &&
                 value.is_array()) {
        for (const auto& r : value) merged["required"].push_back(r);
      } else {
        merged[key] = value;
      }
    }
  }
  return merged;
}

json instance(const json& schema, const json& root, int depth) {
  if (!schema.is_object() || depth > kMaxDepth) return nullptr;
  if (schema.contains("const")) return schema["const"];
  if (schema.contains("enum") && schema["enum"].is_array() && !schema["enum"].empty()) return schema["enum"][0];
  if (schema.contains("default")) return schema["default"];
  if (schema.contains("$ref") && schema["$ref"].is_string()) {
    const json* target = resolve_ref(schema["$ref"].get<std::string>(), root);
    return target ? instance(*target, root, depth + 1) : json(nullptr);
  }
  for (const char* key : {"anyOf", "oneOf"}) {
    if (schema.contains(key) && schema[key].is_array() && !schema[key].empty()) return instance(schema[key][0], root, depth + 1);
  }
  if (schema.contains("allOf") && schema["allOf"].is_array()) return instance(merged_all_of(schema, root), root, depth + 1);
  const std::string type = type_of(schema);
  if (type == "object") return object_instance(schema, root, depth);
  if (type == "array") return array_instance(schema, root, depth);
  if (type == "string") return string_instance(schema);
  if (type == "integer") {
    return static_cast<int64_t>(
        std::clamp(number_in_bounds(schema, true), -kMaxInstanceInteger, kMaxInstanceInteger));
  }
  if (type == "number") return number_in_bounds(schema, false);
  if (type == "boolean") return false;
  if (type == "null") return nullptr;
  return json::object();
}

}  // namespace

json instance_of_schema(const json& schema) {
  if (schema.is_boolean() || schema.is_null()) return json::object();
  return instance(schema, schema, 0);
}

std::string schema_problems(const json& schema, const json& value) {
  if (!schema.is_object()) return schema.is_boolean() && !schema.get<bool>() ? "the schema is false" : "";
  valijson::Schema compiled;
  try {
    valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
    valijson::adapters::NlohmannJsonAdapter schema_adapter(schema);
    parser.populateSchema(schema_adapter, compiled);
  } catch (const std::exception& e) {
    return std::string("the schema cannot be used: ") + e.what();
  }
  valijson::Validator validator;
  valijson::ValidationResults results;
  valijson::adapters::NlohmannJsonAdapter value_adapter(value);
  if (validator.validate(compiled, value_adapter, &results)) return "";
  std::string out;
  valijson::ValidationResults::Error error;
  while (results.popError(error)) {
    std::string path;
    for (const auto& p : error.context) path += p;
    out += (out.empty() ? "" : "; ") + path + ": " + error.description;
  }
  return out;
}

}  // namespace a3::agent::model_server
