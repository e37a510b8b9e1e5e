// Faults inside the agent, from its dialogue.
#include "rigs/outputs/agent_faults.hpp"

#include <algorithm>
#include <iterator>
#include <map>
#include <set>
#include <string>

#include "agent/conversation/turn.hpp"
#include "agent/tool_catalog.hpp"

namespace a3::rigs {
namespace {

// The catalogue's kind of an MCP action's tool ("motion", "sensor", "network", "query"), or "".
std::string tool_kind(const nlohmann::json& action) {
  if (!action.is_object() || action.value("type", "") != "mcp" || !action.contains("name") || !action["name"].is_string()) {
    return "";
  }
  const agent::McpToolSpec* tool = agent::ToolCatalog::builtin().find_tool(action["name"].get<std::string>());
  return tool != nullptr ? tool->kind : "";
}

std::string command_key(const nlohmann::json& action) {
  return action.value("name", action.value("task", "")) + " " + action.value("args", action.value("payload", nlohmann::json())).dump();
}

struct Scan {
  nlohmann::json faults = nlohmann::json::array();
  std::map<std::string, int> refused_at;      // command key -> turn first refused
  std::set<std::string> reported_refusals;
  std::map<std::string, int> timed_out_at;    // tool name -> turn of a timeout not yet sent again
  std::map<std::string, std::string> kind_of; // tool name -> its catalogue kind
  int last_agent_turn = -1;

  void add(const char* kind, int turn, const std::string& detail) {
    faults.push_back({{"kind", kind}, {"turn", turn}, {"detail", detail}});
  }
  void see_refusal(const nlohmann::json& action, int turn) {
    const std::string key = command_key(action);
    const auto first = refused_at.find(key);
    if (first == refused_at.end()) {
      refused_at[key] = turn;
    } else if (reported_refusals.insert(key).second) {
      add("refused_repeated", turn, action.value("name", "") + " refused again with the same arguments (first refused at turn " +
                                       std::to_string(first->second) + ")");
    }
  }
  void see_agent_turn(const nlohmann::json& t) {
    const int turn = t.value("turn", 0);
    last_agent_turn = turn;
    const nlohmann::json& actions = t.contains("actions") && t["actions"].is_array() ? t["actions"] : nlohmann::json::array();
    const nlohmann::json& obs = t.contains("obs") && t["obs"].is_array() ? t["obs"] : nlohmann::json::array();
    for (std::size_t i = 0; i < actions.size(); ++i) {
      const std::string kind = tool_kind(actions[i]);
      if (kind.empty() || kind == "query") continue;
      const std::string name = actions[i]["name"].get<std::string>();
      kind_of[name] = kind;
      timed_out_at.erase(name);  // sent again
      const std::string status = agent::observation_status(i < obs.size() ? obs[i] : nlohmann::json());
      if (status == "refused") see_refusal(actions[i], turn);
      if (status == "timeout") {
        timed_out_at[name] = turn;
      } else if (kind == "motion" && status != "refused" && status != "error") {
        forget_kind("motion");  // the vehicle took a later motion command: the lost ones are moot
      }
    }
  }
  void forget_kind(const std::string& kind) {
    for (auto it = timed_out_at.begin(); it != timed_out_at.end();) {
      it = kind_of[it->first] == kind ? timed_out_at.erase(it) : std::next(it);
    }
  }
  void finish() {
    for (const auto& [name, turn] : timed_out_at) {
      if (turn < last_agent_turn) add("timeout_not_retried", turn, name + " timed out and was never sent again");
    }
  }
};

}  // namespace

nlohmann::json find_agent_faults(const nlohmann::json& dialogue) {
  Scan scan;
  if (!dialogue.is_array()) return scan.faults;
  for (const auto& t : dialogue) {
    if (t.is_object() && t.value("speaker", "") == "agent") scan.see_agent_turn(t);
  }
  scan.finish();
  std::stable_sort(scan.faults.begin(), scan.faults.end(),
                   [](const nlohmann::json& a, const nlohmann::json& b) { return a["turn"].get<int>() < b["turn"].get<int>(); });
  return scan.faults;
}

}  // namespace a3::rigs
