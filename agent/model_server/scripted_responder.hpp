// The "scripted" responder of `a3rig serve-model`: answers the llm agent's turn requests with
// the rig's scripted policy, so that closed-loop `a3rig run --agent llm` runs can be tested
// offline. It reads the context block (llm/context_json.hpp) of the request's last user
// message that carries one, rebuilds the AgentContext (mission, airspace, dialogue, telemetry,
// n_t, turn numbers), and answers with agent::ScriptedAgent's decision:
//   without `tools` (or tool_choice "none")  the reply JSON {"intent", "text", "actions"} as text
//   with `tools`  tool calls: one per action (MCP tools by name, A2A tasks as a2a_<task>, the
//                 arguments being the action's args / payload), then report_turn {intent, text}
//                 when the request offers it (content null), else the text as content; every
//                 offered function must be one of the tool catalog's (else 400 naming it)
// A request without a context block (any other client) gets a generic answer: with tools, a
// call of the chosen (or first) function with arguments generated from its schema; without, a
// short text. It keeps no state between requests: the scripted agent's plan
// is rebuilt by replaying its earlier turns of the dialogue (each decided again on the context
// it had then), so the answer depends only on the request. Token usage is estimated from
// character counts, ~4 characters per token (prompt: every message's content; completion: the
// reply; model_server.hpp's estimate_tokens), as OpenAI's rule of thumb for English text.
#pragma once

#include <string>

#include "agent/conversation/agent.hpp"
#include "agent/model_server/model_responder.hpp"
#include "agent/tool_catalog.hpp"

namespace a3::agent::model_server {

class ScriptedResponder final : public ModelResponder {
 public:
  explicit ScriptedResponder(const ToolCatalog& tools = ToolCatalog::builtin()) : tools_(tools) {}
  std::string name() const override { return "scripted"; }
  // Throws std::invalid_argument (HTTP 400) when the context block is not a usable context
  // (the message names the field), BadRequest when `tools` offers a function not in the catalog.
  ResponderReply respond(const nlohmann::json& request) override;

 private:
  AgentDecision decide(const nlohmann::json& context_block) const;

  const ToolCatalog& tools_;
};

}  // namespace a3::agent::model_server
