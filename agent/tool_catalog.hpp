// The one registry of what an agent can do: the tools it may call (MCP), the tasks it may send
// to peers (A2A), and the call that ends its turn (report_turn), with the JSON Schemas of their
// arguments (agent/tool_catalog.json, compiled in). Everything that lists or dispatches them
// reads it from here: the tool server checks every call against it before anything reaches the
// vehicle and dispatches by name; the llm agent's prompt lists it; the OpenAI function
// definitions (native tool calling) and MCP `tools/list` are made from it (functions()).
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

// The call that ends an agent's turn: {"intent", "text"} (catalog section "turn").
struct TurnCallSpec {
  std::string name;  // "report_turn"
  std::string description;
  nlohmann::json args_schema;
};

// One callable function, as a tool-calling model (OpenAI `tools`) or an MCP client
// (`tools/list`) sees it: every MCP tool under its own name, every A2A task as "a2a_<task>"
// (its arguments are the task's payload; the peer is implied), and report_turn.
struct FunctionSpec {
  enum class Kind { kMcpTool, kA2aTask, kTurn };
  Kind kind = Kind::kMcpTool;
  std::string name;         // the function name: [a-zA-Z0-9_]{1,64}
  std::string description;  // A2A tasks: prefixed with who answers
  nlohmann::json input_schema;
  const McpToolSpec* tool = nullptr;  // kMcpTool
  const A2aTaskSpec* task = nullptr;  // kA2aTask
};

// A function call turned into an α³-Bench action, or what is wrong with it.
struct CallAsAction {
  // {"type":"mcp","name","args"} | {"type":"a2a","task","to","payload"}; for report_turn its
  // arguments {"intent", "text"}
  nlohmann::json action;
  bool ends_turn = false; // report_turn
  std::string problem;    // "" when usable
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
  const TurnCallSpec& turn_call() const { return turn_call_; }
  const nlohmann::json& json() const { return json_; }

  // Every callable function (MCP tools, then A2A tasks, then report_turn), in catalog order.
  const std::vector<FunctionSpec>& functions() const { return functions_; }
  const FunctionSpec* find_function(const std::string& name) const;
  // The function name of an α³ action ("a2a_<task>" for A2A), "" when it is not one.
  static std::string function_name_of(const nlohmann::json& action);
  // OpenAI chat-completions `tools`: [{"type":"function","function":{name,description,parameters}}].
  nlohmann::json openai_tools() const;
  // MCP `tools/list` entries: [{"name","title","description","inputSchema"}].
  nlohmann::json mcp_tools() const;
  // A call of function `name` with `arguments` (an object, or a JSON text of one as OpenAI
  // sends it) as an α³ action, checked against the schema; `problem` names what is wrong.
  CallAsAction action_from_call(const std::string& name, const nlohmann::json& arguments) const;

  // "" when the arguments satisfy the tool's schema, else the problems, naming each field
  // ("args/altitude_m: Expected number greater than or equal to 1").
  std::string check_args(const McpToolSpec& tool, const nlohmann::json& args) const;
  std::string check_payload(const A2aTaskSpec& task, const nlohmann::json& payload) const;
  std::string check_turn_call(const nlohmann::json& args) const;

 private:
  void build_functions();

  nlohmann::json json_;
  std::vector<McpToolSpec> tools_;
  std::vector<A2aTaskSpec> tasks_;
  TurnCallSpec turn_call_;
  std::vector<FunctionSpec> functions_;
  std::map<std::string, std::unique_ptr<valijson::Schema>> schemas_;  // "mcp:NAME" / "a2a:TASK" / "turn"
};

}  // namespace a3::agent
