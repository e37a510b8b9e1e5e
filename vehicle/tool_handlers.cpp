// The registry of the vehicle's tool handlers and its check against the tool catalog.
#include "vehicle/tool_handlers.hpp"

#include <stdexcept>

namespace a3::vehicle {
namespace {

template <typename Handler>
void add_handler(std::map<std::string, Handler>& handlers, const std::string& what, const std::string& name,
                 Handler handler) {
  if (name.empty()) throw std::invalid_argument("vehicle " + what + " handler: empty name");
  if (!handler) throw std::invalid_argument("vehicle " + what + " handler '" + name + "': empty function");
  if (!handlers.emplace(name, std::move(handler)).second) {
    throw std::invalid_argument("vehicle " + what + " handler '" + name + "': registered twice");
  }
}

template <typename Handler>
const Handler* find_handler(const std::map<std::string, Handler>& handlers, const std::string& name) {
  const auto it = handlers.find(name);
  return it == handlers.end() ? nullptr : &it->second;
}

}  // namespace

void ToolHandlers::add_tool(const std::string& name, ToolHandler handler) {
  add_handler(tools_, "tool", name, std::move(handler));
}

void ToolHandlers::add_task(const std::string& task, TaskHandler handler) {
  add_handler(tasks_, "task", task, std::move(handler));
}

const ToolHandler* ToolHandlers::find_tool(const std::string& name) const { return find_handler(tools_, name); }

const TaskHandler* ToolHandlers::find_task(const std::string& task) const { return find_handler(tasks_, task); }

void ToolHandlers::check_against(const ToolCatalog& catalog) const {
  for (const auto& tool : catalog.tools()) {
    if (!tools_.count(tool.name)) {
      throw std::invalid_argument("tool catalog: MCP tool '" + tool.name + "' has no handler on the vehicle");
    }
  }
  for (const auto& task : catalog.tasks()) {
    if (!tasks_.count(task.task)) {
      throw std::invalid_argument("tool catalog: A2A task '" + task.task + "' has no handler on the vehicle");
    }
  }
  for (const auto& [name, handler] : tools_) {
    if (catalog.find_tool(name) == nullptr) {
      throw std::invalid_argument("vehicle tool handler '" + name + "' has no entry in the tool catalog's \"mcp\" section");
    }
  }
  for (const auto& [task, handler] : tasks_) {
    if (catalog.find_task(task) == nullptr) {
      throw std::invalid_argument("vehicle task handler '" + task + "' has no entry in the tool catalog's \"a2a\" section");
    }
  }
}

}  // namespace a3::vehicle
