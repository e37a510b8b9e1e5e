// The tool catalog and argument checking (valijson over nlohmann::json).
#include "agent/tool_catalog.hpp"

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include <cctype>
#include <stdexcept>
#include <utility>
#include <vector>

#include "agent/tool_catalog_json.hpp"
#include "common/json_text.hpp"

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

constexpr const char* kA2aPrefix = "a2a_";

bool valid_function_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
  }
  return true;
}

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
  if (catalog.contains("turn")) {
    if (!catalog["turn"].is_array() || catalog["turn"].size() != 1) {
      throw std::invalid_argument("tool catalog: 'turn' must be an array of one entry (the call that ends a turn)");
    }
    const auto& t = catalog["turn"][0];
    turn_call_ = {string_field(t, "name", "the turn call"), string_field(t, "description", "the turn call"),
                  t.value("args", nlohmann::json::object())};
    schemas_["turn"] = parse_schema(turn_call_.args_schema, "the turn call");
  }
  build_functions();
}

void ToolCatalog::build_functions() {
  for (const auto& t : tools_) {
    functions_.push_back({FunctionSpec::Kind::kMcpTool, t.name, t.description, t.args_schema, &t, nullptr});
  }
  for (const auto& t : tasks_) {
    functions_.push_back({FunctionSpec::Kind::kA2aTask, kA2aPrefix + t.task,
                          "A2A task '" + t.task + "' to " + t.to + ": " + t.description, t.payload_schema, nullptr, &t});
  }
  if (!turn_call_.name.empty()) {
    functions_.push_back({FunctionSpec::Kind::kTurn, turn_call_.name, turn_call_.description, turn_call_.args_schema,
                          nullptr, nullptr});
  }
  for (std::size_t i = 0; i < functions_.size(); ++i) {
    if (!valid_function_name(functions_[i].name)) {
      throw std::invalid_argument("tool catalog: '" + functions_[i].name +
                                  "' is not usable as a function name (letters, digits, '_' and '-', at most 64)");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (functions_[j].name == functions_[i].name) {
        throw std::invalid_argument("tool catalog: two entries are called '" + functions_[i].name + "'");
      }
    }
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

std::string ToolCatalog::check_turn_call(const nlohmann::json& args) const {
  if (turn_call_.name.empty()) return "this tool catalog has no turn call";
  return check(*schemas_.at("turn"), args, "args");
}

const FunctionSpec* ToolCatalog::find_function(const std::string& name) const {
  for (const auto& f : functions_) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

std::string ToolCatalog::function_name_of(const nlohmann::json& action) {
  if (!action.is_object()) return "";
  const std::string type = action.value("type", "");
  if (type == "mcp" && action.contains("name") && action["name"].is_string()) return action["name"].get<std::string>();
  if (type == "a2a" && action.contains("task") && action["task"].is_string()) {
    return kA2aPrefix + action["task"].get<std::string>();
  }
  return "";
}

nlohmann::json ToolCatalog::openai_tools() const {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& f : functions_) {
    out.push_back({{"type", "function"},
                   {"function", {{"name", f.name}, {"description", f.description}, {"parameters", f.input_schema}}}});
  }
  return out;
}

nlohmann::json ToolCatalog::mcp_tools() const {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& f : functions_) {
    nlohmann::json schema = f.input_schema;
    if (!schema.contains("type")) schema["type"] = "object";  // MCP requires an object schema
    out.push_back({{"name", f.name}, {"description", f.description}, {"inputSchema", schema}});
  }
  return out;
}

CallAsAction ToolCatalog::action_from_call(const std::string& name, const nlohmann::json& arguments) const {
  CallAsAction out;
  const FunctionSpec* f = find_function(name);
  if (f == nullptr) {
    std::string names;
    for (const auto& g : functions_) names += (names.empty() ? "" : ", ") + g.name;
    out.problem = "unknown function '" + name + "'; the functions are: " + names;
    return out;
  }
  nlohmann::json args = arguments;
  if (args.is_string()) {
    const std::string text = args.get<std::string>();
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
      args = nlohmann::json::object();
    } else {
      std::string problem;
      auto parsed = common::try_parse_json_text(text, &problem);
      if (!parsed) {
        out.problem = name + ": arguments are not JSON (" + problem + "): " +
                      common::dump_json_text(nlohmann::json(text.substr(0, 200)));
        return out;
      }
      args = std::move(*parsed);
    }
  }
  if (args.is_null()) args = nlohmann::json::object();
  if (!args.is_object()) {
    out.problem = name + ": arguments must be a JSON object, got " + std::string(args.type_name());
    return out;
  }
  std::string problem;
  switch (f->kind) {
    case FunctionSpec::Kind::kMcpTool:
      problem = check_args(*f->tool, args);
      out.action = {{"type", "mcp"}, {"name", f->tool->name}, {"args", args}};
      break;
    case FunctionSpec::Kind::kA2aTask:
      problem = check_payload(*f->task, args);
      out.action = {{"type", "a2a"}, {"task", f->task->task}, {"to", f->task->to}, {"payload", args}};
      break;
    case FunctionSpec::Kind::kTurn:
      problem = check_turn_call(args);
      out.action = args;  // {"intent", "text"}
      out.ends_turn = true;
      break;
  }
  if (!problem.empty()) out.problem = name + ": " + problem;
  return out;
}

}  // namespace a3::agent
