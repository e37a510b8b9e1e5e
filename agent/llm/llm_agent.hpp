// The llm agent: each turn asks an OpenAI-compatible model (through LlmClient) for the next
// agent turn — the prompt of llm_prompt.hpp, the reply parsed and checked by llm_reply.hpp.
// A reply that cannot be used (the call failed, not JSON, an unknown tool, arguments against
// the schema, ...) is retried with progressively stricter instructions, at most 3 attempts as
// the α³-Bench paper does: attempt 2 restates the exact reply format and the problems found,
// attempt 3 adds strict rules (only the JSON object, only these tool names and task/peer pairs,
// only the agent's own turn). The decision carries the attempts made, a log of each attempt
// (outcome, problems, usage, wall time), the summed token usage, and the measured wall time of
// the whole turn as latency_s. After the last failed attempt the decision has an error and no
// actions: the turn is recorded as failed and the episode goes on. The API key stays inside
// the client; anything recorded is also scrubbed of it.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "agent/conversation/agent.hpp"
#include "agent/llm/llm_client.hpp"
#include "agent/llm/llm_prompt.hpp"

namespace a3::agent::llm {

struct LlmAgentOptions {
  int max_attempts = 3;
  DialogueLimits dialogue;
  std::size_t recorded_reply_chars = 1500;  // an unusable reply kept in the attempt log, cut to this
};

// One chat-completions call (LlmClient::chat, or a test double).
using ChatFunction = std::function<LlmCallResult(const std::vector<ChatMessage>&)>;

class LlmAgent final : public Agent {
 public:
  explicit LlmAgent(std::unique_ptr<LlmClient> client, const ToolCatalog& tools = ToolCatalog::builtin(),
                    LlmAgentOptions options = {});
  // `secret` (may be empty) is scrubbed from everything the decision records.
  LlmAgent(ChatFunction chat, std::string secret, const ToolCatalog& tools = ToolCatalog::builtin(),
           LlmAgentOptions options = {});

  std::string name() const override { return "llm"; }
  AgentDecision decide(const AgentContext& context) override;

 private:
  std::unique_ptr<LlmClient> client_;
  ChatFunction chat_;
  std::string secret_;
  const ToolCatalog& tools_;
  LlmAgentOptions options_;
};

}  // namespace a3::agent::llm
