// The messages of one llm agent turn in native tool-calling mode. The system message gives the
// role and the safety rules and says how to act: by calling the functions (OpenAI `tools`, made
// from the tool registry: MCP tools by name, A2A tasks as a2a_<task>) and report_turn once per
// turn with its intent and text; no reply format. Then the dialogue so far as chat history: an
// agent turn is an assistant message with its tool_calls (the ids the model gave, remembered per
// turn; made up for turns it did not make) followed by one `role: "tool"` message per call with
// that call's observation (report_turn's says the turn was reported); a supervisor turn is a
// user message. The history is the context's dialogue with the context's DialogueLimits (the
// oldest turns' observations cut to their status when it is too long). Last, the turn's user
// message, as json mode builds it (ending with the ```json context block that
// `serve-model --responder scripted` rebuilds the context from). Retries add a correction.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "agent/llm/llm_prompt.hpp"
#include "agent/llm/native_reply.hpp"

namespace a3::agent::llm {

// The calls of the agent's earlier turns, by turn number.
using TurnCallMemory = std::map<int, TurnCalls>;

// attempt 3 adds strict rules (only these functions, arguments by their schemas).
std::string native_system_prompt(const ToolCatalog& tools, int attempt = 1);

// The earlier turns as chat messages (see above).
std::vector<ChatMessage> history_messages(const AgentContext& context, const ToolCatalog& tools,
                                          const TurnCallMemory& memory, const DialogueLimits& limits = {});

// The correction sent before attempt `attempt` (2 or 3).
std::string native_correction(const ToolCatalog& tools, int attempt, const FailedAttempt& failure);

// system, history, the turn's user message[, the correction]. `failure` is required for
// attempts 2 and 3.
std::vector<ChatMessage> build_native_messages(const AgentContext& context, const ToolCatalog& tools,
                                               const TurnCallMemory& memory, int attempt = 1,
                                               const FailedAttempt* failure = nullptr,
                                               const DialogueLimits& limits = {});

// The request of a native turn: those messages, every function of the registry as `tools`,
// tool_choice "required".
ChatRequest native_request(const AgentContext& context, const ToolCatalog& tools, const TurnCallMemory& memory,
                           int attempt, const FailedAttempt* failure, const DialogueLimits& limits);

}  // namespace a3::agent::llm
