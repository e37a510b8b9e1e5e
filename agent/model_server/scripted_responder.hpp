// The "scripted" responder of `a3rig serve-model`: answers the llm agent's turn requests with
// the rig's scripted policy, so that closed-loop `a3rig run --agent llm` runs can be tested
// offline. It reads the context block (llm/context_json.hpp) of the request's last user
// message that carries one, rebuilds the AgentContext (mission, airspace, dialogue, telemetry,
// n_t, turn numbers), and answers with agent::ScriptedAgent's decision as the reply JSON
// {"intent", "text", "actions"}. It keeps no state between requests: the scripted agent's plan
// is rebuilt by replaying its earlier turns of the dialogue (each decided again on the context
// it had then), so the answer depends only on the request. Token usage is estimated from
// character counts, ~4 characters per token (prompt: every message's content; completion: the
// reply; model_server.hpp's estimate_tokens), as OpenAI's rule of thumb for English text.
#pragma once

#include <string>

#include "agent/model_server/model_responder.hpp"
#include "agent/tool_catalog.hpp"

namespace a3::agent::model_server {

class ScriptedResponder final : public ModelResponder {
 public:
  explicit ScriptedResponder(const ToolCatalog& tools = ToolCatalog::builtin()) : tools_(tools) {}
  std::string name() const override { return "scripted"; }
  // Throws std::invalid_argument (HTTP 400) when the request carries no context block or the
  // block is not a usable context (the message names the field).
  ResponderReply respond(const nlohmann::json& request) override;

 private:
  const ToolCatalog& tools_;
};

}  // namespace a3::agent::model_server
