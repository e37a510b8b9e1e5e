// The scripted policy behind an OpenAI-compatible endpoint.
#include "agent/model_server/scripted_responder.hpp"

#include <optional>
#include <stdexcept>
#include <vector>

#include "agent/conversation/scripted_agent.hpp"
#include "agent/llm/context_json.hpp"
#include "agent/model_server/model_server.hpp"

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

}  // namespace

ResponderReply ScriptedResponder::respond(const nlohmann::json& request) {
  if (!request.is_object() || !request.contains("messages") || !request["messages"].is_array()) {
    throw std::invalid_argument("request: 'messages' must be an array of chat messages");
  }
  const auto& messages = request["messages"];
  std::optional<nlohmann::json> block;
  for (std::size_t i = messages.size(); i-- > 0 && !block;) {
    if (messages[i].is_object() && messages[i].value("role", "") == "user") {
      block = llm::find_context_block(message_text(messages[i]));
    }
  }
  if (!block) {
    throw std::invalid_argument(
        "the scripted responder answers a3rig's llm agent turns only: no user message of the request carries the "
        "context block (a JSON object with \"" + std::string(llm::kContextMarker) + "\": " +
        std::to_string(llm::kContextVersion) + ", as `a3rig run --agent llm` sends)");
  }
  const llm::RebuiltContext context = llm::context_from_json(*block);

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
  const AgentDecision d = agent.decide(context.view(tools_));

  ResponderReply reply;
  reply.content = nlohmann::json({{"intent", d.intent}, {"text", d.text}, {"actions", d.actions}}).dump();
  const int64_t prompt_tokens = estimate_tokens(prompt_characters(request));
  const int64_t completion_tokens = estimate_tokens(reply.content.size());
  reply.usage = {{"prompt_tokens", prompt_tokens},
                 {"completion_tokens", completion_tokens},
                 {"total_tokens", prompt_tokens + completion_tokens}};
  return reply;
}

}  // namespace a3::agent::model_server
