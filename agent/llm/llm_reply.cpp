// Reply parsing and checking.
#include "agent/llm/llm_reply.hpp"

#include "agent/llm/json_extract.hpp"

namespace a3::agent::llm {
namespace {

// ToolCatalog's checks return "args/x: ...; args/y: ..."; each problem gets the action's place.
void add_schema_problems(const std::string& found, const std::string& prefix, std::vector<std::string>& problems) {
  std::size_t start = 0;
  while (start < found.size()) {
    std::size_t end = found.find("; ", start);
    if (end == std::string::npos) end = found.size();
    problems.push_back(prefix + found.substr(start, end - start));
    start = end + 2;
  }
}

std::string known_tools(const ToolCatalog& tools) {
  std::string out;
  for (const auto& t : tools.tools()) out += (out.empty() ? "" : ", ") + t.name;
  return out;
}

std::string known_tasks(const ToolCatalog& tools) {
  std::string out;
  for (const auto& t : tools.tasks()) out += (out.empty() ? "" : ", ") + t.task;
  return out;
}

std::string type_of(const nlohmann::json& j) { return j.type_name(); }

// Copying args and payloads recurses on their depth: safe because replies are parsed with
// common/json_text's depth bound (extract_json_object).
nlohmann::json check_action(const nlohmann::json& a, std::size_t i, const ToolCatalog& tools,
                            std::vector<std::string>& problems) {
  const std::string where = "actions/" + std::to_string(i);
  if (!a.is_object()) {
    problems.push_back(where + ": expected an object, got " + type_of(a));
    return nullptr;
  }
  if (!a.contains("type") || !a["type"].is_string()) {
    problems.push_back(where + "/type: missing (\"mcp\" or \"a2a\")");
    return nullptr;
  }
  const std::string type = a["type"].get<std::string>();
  if (type == "mcp") {
    if (!a.contains("name") || !a["name"].is_string()) {
      problems.push_back(where + "/name: missing (the tool's name)");
      return nullptr;
    }
    const std::string name = a["name"].get<std::string>();
    const McpToolSpec* tool = tools.find_tool(name);
    if (tool == nullptr) {
      problems.push_back(where + "/name: unknown tool '" + name + "' (known: " + known_tools(tools) + ")");
      return nullptr;
    }
    nlohmann::json args = a.contains("args") ? a["args"] : nlohmann::json::object();
    if (args.is_null()) args = nlohmann::json::object();
    if (!args.is_object()) {
      problems.push_back(where + "/args: expected an object, got " + type_of(args));
      return nullptr;
    }
    const std::string found = tools.check_args(*tool, args);
    if (!found.empty()) {
      add_schema_problems(found, where + "/", problems);
      return nullptr;
    }
    return {{"type", "mcp"}, {"name", name}, {"args", args}};
  }
  if (type == "a2a") {
    if (!a.contains("task") || !a["task"].is_string()) {
      problems.push_back(where + "/task: missing (the A2A task's name)");
      return nullptr;
    }
    const std::string task_name = a["task"].get<std::string>();
    const A2aTaskSpec* task = tools.find_task(task_name);
    if (task == nullptr) {
      problems.push_back(where + "/task: unknown A2A task '" + task_name + "' (known: " + known_tasks(tools) + ")");
      return nullptr;
    }
    if (!a.contains("to") || !a["to"].is_string()) {
      problems.push_back(where + "/to: missing (task '" + task_name + "' goes to '" + task->to + "')");
      return nullptr;
    }
    const std::string to = a["to"].get<std::string>();
    if (to != task->to) {
      problems.push_back(where + "/to: task '" + task_name + "' goes to '" + task->to + "', not '" + to + "'");
      return nullptr;
    }
    nlohmann::json payload = a.contains("payload") ? a["payload"] : nlohmann::json::object();
    if (payload.is_null()) payload = nlohmann::json::object();
    if (!payload.is_object()) {
      problems.push_back(where + "/payload: expected an object, got " + type_of(payload));
      return nullptr;
    }
    const std::string found = tools.check_payload(*task, payload);
    if (!found.empty()) {
      add_schema_problems(found, where + "/", problems);
      return nullptr;
    }
    return {{"type", "a2a"}, {"task", task_name}, {"to", to}, {"payload", payload}};
  }
  problems.push_back(where + "/type: expected \"mcp\" or \"a2a\", got \"" + type + "\"");
  return nullptr;
}

void parse_into(const std::string& content, const ToolCatalog& tools, ParsedReply& out) {
  if (content.find_first_not_of(" \t\r\n") == std::string::npos) {
    out.problems.push_back("reply: empty");
    return;
  }
  ExtractedObject found = extract_json_object(content);
  if (!found.object) {
    out.problems.push_back("reply: " + found.error);
    return;
  }
  const nlohmann::json& j = *found.object;
  if (!j.contains("intent")) {
    out.problems.push_back("intent: missing (a short snake_case label of the turn)");
  } else if (!j["intent"].is_string() || j["intent"].get<std::string>().empty()) {
    out.problems.push_back("intent: expected a non-empty string");
  } else {
    out.intent = j["intent"].get<std::string>();
  }
  if (j.contains("text") && !j["text"].is_null()) {
    if (j["text"].is_string()) {
      out.text = j["text"].get<std::string>();
    } else {
      out.problems.push_back("text: expected a string, got " + type_of(j["text"]));
    }
  }
  if (!j.contains("actions")) {
    out.problems.push_back("actions: missing (use [] for a turn without actions)");
    return;
  }
  if (!j["actions"].is_array()) {
    out.problems.push_back("actions: expected an array, got " + type_of(j["actions"]));
    return;
  }
  for (std::size_t i = 0; i < j["actions"].size(); ++i) {
    nlohmann::json a = check_action(j["actions"][i], i, tools, out.problems);
    if (!a.is_null()) out.actions.push_back(std::move(a));
  }
}

}  // namespace

std::string ParsedReply::problems_text() const {
  std::string out;
  for (const auto& p : problems) out += (out.empty() ? "" : "; ") + p;
  return out;
}

ParsedReply parse_reply(const std::string& content, const ToolCatalog& tools) {
  ParsedReply out;
  try {
    parse_into(content, tools, out);
  } catch (const std::exception& e) {
    out.problems.push_back(std::string("reply: could not be checked: ") + e.what());
  }
  if (!out.ok()) out.actions = nlohmann::json::array();
  // Problems may quote the reply's bytes; they go into prompts and episode files (JSON).
  for (auto& p : out.problems) p = valid_utf8(p);
  return out;
}

}  // namespace a3::agent::llm
