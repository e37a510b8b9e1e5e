// The tools an agent may call (MCP) and the tasks it may send to peers (A2A), with the JSON
// Schemas of their arguments (agent/tool_catalog.json, compiled in). The tool server checks
// every call against it before anything reaches the vehicle; LLM prompts list it.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace valijson {
class Schema;
}

namespace a3::agent {

struct McpToolSpec {
  std::string name;
  std::string kind;  // "query" | "motion" | "sensor" | "network"
  std::string description;
  nlohmann::json args_schema;
};

struct A2aTaskSpec {
  std::string task;
  std::string to;  // the peer that answers it
  std::string description;
  nlohmann::json payload_schema;
};

class ToolCatalog {
 public:
  // Throws std::invalid_argument when the text is not a catalog (names the problem).
  explicit ToolCatalog(const nlohmann::json& catalog);
  ~ToolCatalog();
  ToolCatalog(const ToolCatalog&) = delete;
  ToolCatalog& operator=(const ToolCatalog&) = delete;

  // The built-in catalog.
  static const ToolCatalog& builtin();

  const McpToolSpec* find_tool(const std::string& name) const;
  const A2aTaskSpec* find_task(const std::string& task) const;
  const std::vector<McpToolSpec>& tools() const { return tools_; }
  const std::vector<A2aTaskSpec>& tasks() const { return tasks_; }
  const nlohmann::json& json() const { return json_; }

  // "" when the arguments satisfy the tool's schema, else the problems, naming each field
  // ("args/altitude_m: Expected number greater than or equal to 1").
  std::string check_args(const McpToolSpec& tool, const nlohmann::json& args) const;
  std::string check_payload(const A2aTaskSpec& task, const nlohmann::json& payload) const;

 private:
  nlohmann::json json_;
  std::vector<McpToolSpec> tools_;
  std::vector<A2aTaskSpec> tasks_;
  std::map<std::string, std::unique_ptr<valijson::Schema>> schemas_;  // "mcp:NAME" / "a2a:TASK"
};

}  // namespace a3::agent
