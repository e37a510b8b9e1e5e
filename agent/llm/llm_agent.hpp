// The llm agent: each turn asks an OpenAI-compatible model (through LlmClient) for the next
// agent turn, in one of two modes (LlmAgentOptions::mode):
// - json (the α³-Bench paper's protocol): the prompt of llm_prompt.hpp asks for a JSON object
//   {intent, text, actions} in the reply's text, parsed and checked by llm_reply.hpp;
// - native tool calling: every function of the tool registry is sent as OpenAI `tools`
//   (tool_choice "required"); the model's tool_calls are the turn's actions and its report_turn
//   call the intent and text (native_reply.hpp); earlier turns go back as chat history with the
//   calls' ids the model gave and their observations as tool messages (native_prompt.hpp).
// A reply that cannot be used (the call failed, not JSON, no function called, an unknown tool,
// arguments against the schema, ...) is retried with progressively stricter instructions, at
// most 3 attempts as the α³-Bench paper does: attempt 2 restates what was wrong and how to
// answer, attempt 3 adds strict rules. The decision carries the attempts made, a log of each
// attempt (outcome, problems, usage, wall time, HTTP status, whether the failure was the
// endpoint's, and for a streamed answer the time to the first and the last token), the summed
// token usage, and the measured wall time of the whole turn as latency_s. After the last failed
// attempt the decision has an error and no actions: the turn is recorded as failed and the
// episode goes on. A call ended by stop_deciding() (Ctrl-C) is an attempt with outcome
// "interrupted" and no further attempt: the decision's error starts with "interrupted: ". The API key stays inside the client; anything recorded is also scrubbed of it.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "agent/conversation/agent.hpp"
#include "agent/llm/llm_client.hpp"
#include "agent/llm/llm_prompt.hpp"
#include "agent/llm/native_prompt.hpp"

namespace a3::agent::llm {

struct LlmAgentOptions {
  int max_attempts = 3;
  DialogueLimits dialogue;
  std::size_t recorded_reply_chars = 1500;  // an unusable reply kept in the attempt log, cut to this
  ToolMode mode = ToolMode::kJson;
};

// One chat-completions call (LlmClient::chat, or a test double).
using ChatFunction = std::function<LlmCallResult(const ChatRequest&)>;

class LlmAgent final : public Agent {
 public:
  explicit LlmAgent(std::unique_ptr<LlmClient> client, const ToolCatalog& tools = ToolCatalog::builtin(),
                    LlmAgentOptions options = {});
  // `secret` (may be empty) is scrubbed from everything the decision records.
  LlmAgent(ChatFunction chat, std::string secret, const ToolCatalog& tools = ToolCatalog::builtin(),
           LlmAgentOptions options = {});

  std::string name() const override { return "llm"; }
  AgentDecision decide(const AgentContext& context) override;
  // Ctrl-C: the call in flight ends within 50 ms and decide() returns the turn as interrupted
  // (its attempt log kept); later decisions are interrupted at once. Any thread.
  void stop_deciding() override;

 private:
  // One attempt's usable turn, or its problems.
  struct Reading {
    std::string intent, text;
    nlohmann::json actions = nlohmann::json::array();
    TurnCalls calls;
    std::vector<std::string> problems;
    std::string reply;  // as recorded for an unusable reply
  };
  ChatRequest request(const AgentContext& context, int attempt, const FailedAttempt* failure) const;
  LlmCallResult call(const ChatRequest& request, bool& threw);
  Reading read(const LlmCallResult& call, int turn_number) const;

  std::unique_ptr<LlmClient> client_;
  ChatFunction chat_;
  std::string secret_;
  const ToolCatalog& tools_;
  LlmAgentOptions options_;
  TurnCallMemory calls_;  // native mode: the calls of each turn this agent made
  std::atomic<bool> stopped_{false};
};

}  // namespace a3::agent::llm
