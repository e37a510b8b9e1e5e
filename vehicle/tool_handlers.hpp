// The vehicle's tool handlers, registered by catalog name: one per MCP tool, one per A2A
// task. The tool server dispatches by name through this registry (no chain of names) and, at
// construction, checks it against the tool catalog both ways. Adding a tool means one catalog
// entry (agent/tool_catalog.json) and one handler registered here (vehicle_tools.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <string>

#include "vehicle/ground_shared.hpp"
#include "vehicle/peer_answer.hpp"
#include "vehicle/vehicle_services.hpp"

namespace a3::vehicle {

// An MCP tool: args already satisfy the catalog's schema; answers through vehicle.finish_*.
using ToolHandler = std::function<void(VehicleServices& vehicle, const nlohmann::json& args)>;
// An A2A task: payload already satisfies the catalog's schema; the peer's answer.
using TaskHandler = std::function<PeerAnswer(VehicleServices& vehicle, const nlohmann::json& payload)>;

class ToolHandlers {
 public:
  // Throws std::invalid_argument when the name is empty or already has a handler.
  void add_tool(const std::string& name, ToolHandler handler);
  void add_task(const std::string& task, TaskHandler handler);

  const ToolHandler* find_tool(const std::string& name) const;  // nullptr when none
  const TaskHandler* find_task(const std::string& task) const;
  std::size_t tool_count() const { return tools_.size(); }
  std::size_t task_count() const { return tasks_.size(); }

  // Throws std::invalid_argument naming a catalog tool or task that has no handler, or a
  // handler that has no catalog entry. The catalog's turn call (report_turn) is not a
  // vehicle tool and needs none.
  void check_against(const ToolCatalog& catalog) const;

 private:
  std::map<std::string, ToolHandler> tools_;
  std::map<std::string, TaskHandler> tasks_;
};

}  // namespace a3::vehicle
