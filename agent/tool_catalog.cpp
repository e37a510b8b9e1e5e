// The tool catalog and argument checking (valijson over nlohmann::json).
#include "agent/tool_catalog.hpp"

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include <stdexcept>
#include <utility>
#include <vector>

#include "agent/tool_catalog_json.hpp"

namespace a3::agent {
namespace {

std::unique_ptr<valijson::Schema> parse_schema(const nlohmann::json& schema, const std::string& what) {
  auto out = std::make_unique<valijson::Schema>();
  try {
    valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
    valijson::adapters::NlohmannJsonAdapter adapter(schema);
    parser.populateSchema(adapter, *out);
  } catch (const std::exception& e) {
    throw std::invalid_argument("tool catalog: schema of " + what + " is not usable: " + e.what());
  }
  return out;
}

std::string check(const valijson::Schema& schema, const nlohmann::json& value, const std::string& root) {
  valijson::Validator validator;
  valijson::ValidationResults results;
  valijson::adapters::NlohmannJsonAdapter adapter(value);
  if (validator.validate(schema, adapter, &results)) return "";
  std::vector<std::pair<std::string, std::string>> errors;
  valijson::ValidationResults::Error error;
  while (results.popError(error)) {
    std::string path = root;
    for (const auto& part : error.context) {
      if (part == "<root>") continue;
      path += "/" + (part.size() >= 2 && part.front() == '[' ? part.substr(1, part.size() - 2) : part);
    }
    errors.emplace_back(path, error.description);
  }
  // valijson also reports each enclosing object ("Failed to validate ..."): keep the specific ones.
  auto summary = [](const std::string& d) { return d.rfind("Failed to validate ", 0) == 0; };
  bool any_specific = false;
  for (const auto& e : errors) any_specific |= !summary(e.second);
  std::string out;
  for (const auto& [path, description] : errors) {
    if (any_specific && summary(description)) continue;
    if (!out.empty()) out += "; ";
    out += path + ": " + description;
  }
  return out;
}

std::string string_field(const nlohmann::json& o, const char* key, const std::string& where) {
  if (!o.contains(key) || !o[key].is_string()) {
    throw std::invalid_argument("tool catalog: " + where + " needs a string '" + key + "'");
  }
  return o[key].get<std::string>();
}

}  // namespace

ToolCatalog::ToolCatalog(const nlohmann::json& catalog) : json_(catalog) {
  if (!catalog.is_object() || !catalog.contains("mcp") || !catalog["mcp"].is_array() ||
      !catalog.contains("a2a") || !catalog["a2a"].is_array()) {
    throw std::invalid_argument("tool catalog: needs arrays 'mcp' and 'a2a'");
  }
  for (const auto& t : catalog["mcp"]) {
    McpToolSpec spec{string_field(t, "name", "an MCP tool"), string_field(t, "kind", "an MCP tool"),
                     string_field(t, "description", "an MCP tool"), t.value("args", nlohmann::json::object())};
    schemas_["mcp:" + spec.name] = parse_schema(spec.args_schema, "tool " + spec.name);
    tools_.push_back(std::move(spec));
  }
  for (const auto& t : catalog["a2a"]) {
    A2aTaskSpec spec{string_field(t, "task", "an A2A task"), string_field(t, "to", "an A2A task"),
                     string_field(t, "description", "an A2A task"), t.value("payload", nlohmann::json::object())};
    schemas_["a2a:" + spec.task] = parse_schema(spec.payload_schema, "task " + spec.task);
    tasks_.push_back(std::move(spec));
  }
}

ToolCatalog::~ToolCatalog() = default;

const ToolCatalog& ToolCatalog::builtin() {
  static const ToolCatalog catalog(nlohmann::json::parse(tool_catalog_json()));
  return catalog;
}

const McpToolSpec* ToolCatalog::find_tool(const std::string& name) const {
  for (const auto& t : tools_) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

const A2aTaskSpec* ToolCatalog::find_task(const std::string& task) const {
  for (const auto& t : tasks_) {
    if (t.task == task) return &t;
  }
  return nullptr;
}

std::string ToolCatalog::check_args(const McpToolSpec& tool, const nlohmann::json& args) const {
  return check(*schemas_.at("mcp:" + tool.name), args, "args");
}

std::string ToolCatalog::check_payload(const A2aTaskSpec& task, const nlohmann::json& payload) const {
  return check(*schemas_.at("a2a:" + task.task), payload, "payload");
}

}  // namespace a3::agent
