// The scripted policy behind an OpenAI-compatible endpoint.
#include "agent/model_server/scripted_responder.hpp"

#include <optional>
#include <stdexcept>
#include <vector>

#include "agent/conversation/scripted_agent.hpp"
#include "agent/llm/context_json.hpp"
#include "agent/model_server/chat_request.hpp"
#include "agent/model_server/model_server.hpp"
#include "agent/model_server/reply_shaping.hpp"

namespace a3::agent::model_server {
namespace {

// A message's text: a string, or OpenAI's list of parts ({"type": "text", "text": ...}).
std::string message_text(const nlohmann::json& m) {
  if (!m.is_object() || !m.contains("content")) return "";
  const auto& c = m["content"];
  if (c.is_string()) return c.get<std::string>();
  std::string out;
  if (c.is_array()) {
    for (const auto& part : c) {
      if (part.is_object() && part.contains("text") && part["text"].is_string()) out += part["text"].get<std::string>();
    }
  }
  return out;
}

bool is_timeout(const nlohmann::json& result) {
  return result.is_object() && result.size() == 1 && result.value("status", "") == "timeout";
}

// What the conversation knew as the latest telemetry when turn `upto` began.
nlohmann::json telemetry_before(const std::vector<Turn>& dialogue, std::size_t upto) {
  nlohmann::json latest = nullptr;
  for (std::size_t i = 0; i < upto; ++i) {
    for (const auto& o : dialogue[i].obs) {
      if (o.is_object() && o.value("tool", "") == "read_telemetry" && o.contains("result") && !is_timeout(o["result"])) {
        latest = o["result"];
      }
    }
  }
  return latest;
}

// The request's last user message that carries a context block, as JSON; nothing when none does.
std::optional<nlohmann::json> context_block(const nlohmann::json& messages) {
  for (std::size_t i = messages.size(); i-- > 0;) {
    if (messages[i].is_object() && messages[i].value("role", "") == "user") {
      if (auto block = llm::find_context_block(message_text(messages[i]))) return block;
    }
  }
  return std::nullopt;
}

bool wants_calls(const ChatOptions& options) {
  return !options.functions.empty() && options.tool_choice != ToolChoice::kNone;
}

void set_usage(ResponderReply& reply, const nlohmann::json& request) {
  std::size_t completion_chars = reply.content.size();
  for (const auto& c : reply.tool_calls) completion_chars += c.name.size() + c.arguments.size();
  const int64_t prompt_tokens = estimate_tokens(prompt_characters(request));
  const int64_t completion_tokens = estimate_tokens(completion_chars);
  reply.usage = {{"prompt_tokens", prompt_tokens},
                 {"completion_tokens", completion_tokens},
                 {"total_tokens", prompt_tokens + completion_tokens}};
}

// Every function the request offers must be one the scripted policy can call.
void check_functions(const ChatOptions& options, const ToolCatalog& tools) {
  for (std::size_t i = 0; i < options.functions.size(); ++i) {
    const std::string name = options.functions[i]["name"].get<std::string>();
    if (tools.find_function(name) != nullptr) continue;
    std::string known;
    for (const auto& f : tools.functions()) known += (known.empty() ? "" : ", ") + f.name;
    const std::string param = "tools[" + std::to_string(i) + "].function.name";
    throw BadRequest(param + " '" + name + "' is not a function the scripted responder can call (a3rig's tool "
                     "catalog has: " + known + ")", param);
  }
}

bool offered(const ChatOptions& options, const std::string& name) { return find_function(options, name) != nullptr; }

// The decision as tool calls: one per action, then report_turn {intent, text} when offered.
void decision_as_calls(const AgentDecision& d, const ChatOptions& options, const std::string& report,
                       ResponderReply& reply) {
  for (const auto& action : d.actions) {
    const std::string name = ToolCatalog::function_name_of(action);
    const nlohmann::json args = action.value("type", "") == "a2a" ? action.value("payload", nlohmann::json::object())
                                                                  : action.value("args", nlohmann::json::object());
    if (!name.empty() && offered(options, name)) reply.tool_calls.push_back({"", name, args.dump()});
  }
  if (offered(options, report)) {
    reply.tool_calls.push_back({"", report, nlohmann::json({{"intent", d.intent}, {"text", d.text}}).dump()});
  } else {
    reply.content = d.text;
  }
}

// A client that is not a3rig: a call of the chosen (or first) function with arguments made from
// its schema, or a short text.
ResponderReply generic_reply(const ChatOptions& options) {
  ResponderReply reply;
  if (wants_calls(options)) {
    const std::string name = options.tool_choice == ToolChoice::kNamed ? options.chosen_function
                                                                        : options.functions.front()["name"].get<std::string>();
    reply.tool_calls.push_back(generated_call(*find_function(options, name)));
    reply.finish_reason = "tool_calls";
    return reply;
  }
  reply.content = "Hello from a3rig's scripted responder. It flies a3rig's llm agent turns (requests carrying a3rig's "
                  "context block); to other requests it gives this answer.";
  return reply;
}

}  // namespace

AgentDecision ScriptedResponder::decide(const nlohmann::json& block) const {
  const llm::RebuiltContext context = llm::context_from_json(block);
  // Replay the earlier agent turns so that the plan stands where it stood.
  ScriptedAgent agent;
  for (std::size_t j = 0; j < context.dialogue.size(); ++j) {
    const Turn& t = context.dialogue[j];
    if (t.speaker != "agent") continue;
    const std::vector<Turn> before(context.dialogue.begin(), context.dialogue.begin() + static_cast<std::ptrdiff_t>(j));
    AgentContext then = context.view(tools_);
    then.dialogue = &before;
    then.net = t.net;
    then.last_telemetry = telemetry_before(context.dialogue, j);
    then.turn_number = t.number;
    then.mission_time_s = t.started_s;
    agent.decide(then);
  }
  return agent.decide(context.view(tools_));
}

ResponderReply ScriptedResponder::respond(const nlohmann::json& request) {
  if (!request.is_object() || !request.contains("messages") || !request["messages"].is_array()) {
    throw std::invalid_argument("request: 'messages' must be an array of chat messages");
  }
  const ChatOptions options = chat_options(request);
  const std::optional<nlohmann::json> block = context_block(request["messages"]);
  ResponderReply reply;
  if (!block) {
    reply = generic_reply(options);
  } else if (wants_calls(options)) {
    check_functions(options, tools_);
    decision_as_calls(decide(*block), options, tools_.turn_call().name, reply);
    if (!reply.tool_calls.empty()) reply.finish_reason = "tool_calls";
  } else {
    const AgentDecision d = decide(*block);
    reply.content = nlohmann::json({{"intent", d.intent}, {"text", d.text}, {"actions", d.actions}}).dump();
  }
  set_usage(reply, request);
  return reply;
}

}  // namespace a3::agent::model_server
