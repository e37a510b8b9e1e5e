// Prompt and chat history of the llm agent in native tool-calling mode.
#include "agent/llm/native_prompt.hpp"

#include <stdexcept>

namespace a3::agent::llm {
namespace {

using nlohmann::json;

const char* kReportedResult = "Turn reported. The supervisor speaks next.";

std::string native_instructions(const ToolCatalog& tools) {
  return "How to act: the MCP tools and A2A tasks are the functions you are given. Call a tool by its name; an "
         "A2A task as a2a_<task> with its payload as the arguments (it goes to the peer its description names). "
         "Each call's result is its observation, as the vehicle or the peer answered across the link. In every "
         "turn, call the functions of that turn's actions (several at once when the turn needs them), and call " +
         tools.turn_call().name +
         " exactly once with the turn's intent (a short snake_case label, as in the α³-Bench corpus: "
         "preflight_check, arm_and_takeoff, navigate_to_target, area_survey, status_report, return_to_home, "
         "land_at_home, ...) and the words you say to the supervisor. A turn that needs no action calls only " +
         tools.turn_call().name + ". Do not answer with text alone.\n";
}

std::string function_names(const ToolCatalog& tools) {
  std::string out;
  for (const auto& f : tools.functions()) out += (out.empty() ? "" : ", ") + f.name;
  return out;
}

std::string strict_rules(const ToolCatalog& tools) {
  return "STRICT RULES for this turn:\n"
         "- Act only by calling functions; a reply with text alone is not usable.\n"
         "- Functions: only " + function_names(tools) + ".\n"
         "- Arguments: only the properties their schemas list, with the types and ranges they allow; {} when a "
         "function takes none.\n"
         "- Call " + tools.turn_call().name + " once, with a non-empty intent.\n"
         "- When unsure, call read_telemetry and " + tools.turn_call().name +
         " with intent status_report.\n";
}

// The call an earlier action was made by: the remembered one when it is that action's function,
// else one made up from the action.
ToolCall call_of(const json& action, const TurnCalls* remembered, std::size_t i, int turn) {
  const std::string name = ToolCatalog::function_name_of(action);
  if (remembered != nullptr && i < remembered->action_calls.size() && remembered->action_calls[i].name == name) {
    return remembered->action_calls[i];
  }
  const json args = action.value("type", "") == "a2a" ? action.value("payload", json::object())
                                                      : action.value("args", json::object());
  return {"call_" + std::to_string(turn) + "_" + std::to_string(i), name, args.dump()};
}

ToolCall report_of(const json& turn, const TurnCalls* remembered, const ToolCatalog& tools) {
  if (remembered != nullptr && remembered->report_call) return *remembered->report_call;
  const json args = {{"intent", turn.value("intent", "")}, {"text", turn.value("text", "")}};
  return {"call_" + std::to_string(turn.value("turn", 0)) + "_report", tools.turn_call().name, args.dump()};
}

std::string dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

void add_agent_turn(const json& turn, const ToolCatalog& tools, const TurnCallMemory& memory,
                    std::vector<ChatMessage>& out) {
  const int number = turn.value("turn", 0);
  const auto it = memory.find(number);
  const TurnCalls* remembered = it == memory.end() ? nullptr : &it->second;
  const json actions = turn.value("actions", json::array());
  const json obs = turn.value("obs", json::array());
  if (actions.empty() && turn.value("intent", "") == "agent_error") {  // a failed turn: what it was
    out.push_back({"assistant", turn.value("text", "")});
    return;
  }
  ChatMessage assistant{"assistant", ""};
  for (std::size_t i = 0; i < actions.size(); ++i) assistant.tool_calls.push_back(call_of(actions[i], remembered, i, number));
  assistant.tool_calls.push_back(report_of(turn, remembered, tools));
  out.push_back(assistant);
  for (std::size_t i = 0; i < actions.size(); ++i) {
    const std::string result = i < obs.size() ? dump(obs[i]) : "no observation came back";
    out.push_back({"tool", result, {}, assistant.tool_calls[i].id});
  }
  out.push_back({"tool", kReportedResult, {}, assistant.tool_calls.back().id});
}

std::string supervisor_message(const json& turn) {
  return "Supervisor (turn " + std::to_string(turn.value("turn", 0)) + ", intent " + turn.value("intent", "") +
         "): " + turn.value("text", "");
}

// The role and safety rules as json mode states them, pointing at the functions instead of a
// list in the text.
std::string role_and_safety_for_functions() {
  std::string text = role_and_safety_text();
  static const std::string kListed = "listed below";
  for (std::size_t at = text.find(kListed); at != std::string::npos; at = text.find(kListed, at)) {
    text.replace(at, kListed.size(), "given to you as functions");
  }
  return text;
}

}  // namespace

std::string native_system_prompt(const ToolCatalog& tools, int attempt) {
  std::string out = role_and_safety_for_functions() + "\n" + native_instructions(tools);
  if (attempt >= 3) out += "\n" + strict_rules(tools);
  return out;
}

std::vector<ChatMessage> history_messages(const AgentContext& c, const ToolCatalog& tools,
                                          const TurnCallMemory& memory, const DialogueLimits& limits) {
  std::vector<ChatMessage> out;
  const json dialogue = context_to_json(c, limits)["dialogue"];
  for (const json& turn : dialogue) {
    if (turn.value("speaker", "") == "agent") {
      add_agent_turn(turn, tools, memory, out);
    } else {
      out.push_back({"user", supervisor_message(turn)});
    }
  }
  return out;
}

std::string native_correction(const ToolCatalog& tools, int attempt, const FailedAttempt& failure) {
  std::string out = failure_text(failure);
  out += "\nAct again, for the same turn: call the functions of its actions and " + tools.turn_call().name +
         " once with its intent and text.\n";
  if (attempt >= 3) out += "\n" + strict_rules(tools);
  return out;
}

std::vector<ChatMessage> build_native_messages(const AgentContext& c, const ToolCatalog& tools,
                                               const TurnCallMemory& memory, int attempt,
                                               const FailedAttempt* failure, const DialogueLimits& limits) {
  if (attempt < 1) throw std::invalid_argument("build_native_messages: attempt must be >= 1, got " + std::to_string(attempt));
  if (attempt > 1 && failure == nullptr) {
    throw std::invalid_argument("build_native_messages: attempt " + std::to_string(attempt) + " needs the failed attempt");
  }
  std::vector<ChatMessage> messages = {{"system", native_system_prompt(tools, attempt)}};
  for (auto& m : history_messages(c, tools, memory, limits)) messages.push_back(std::move(m));
  messages.push_back({"user", turn_prompt(c, limits, ToolMode::kNative)});
  if (attempt > 1) messages.push_back({"user", native_correction(tools, attempt, *failure)});
  return messages;
}

ChatRequest native_request(const AgentContext& c, const ToolCatalog& tools, const TurnCallMemory& memory, int attempt,
                           const FailedAttempt* failure, const DialogueLimits& limits) {
  ChatRequest r;
  r.messages = build_native_messages(c, tools, memory, attempt, failure, limits);
  r.tools = tools.openai_tools();
  r.tool_choice = "required";
  return r;
}

}  // namespace a3::agent::llm
