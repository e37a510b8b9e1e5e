// The messages of one llm agent turn. The system message gives the agent's role (an autonomous
// UAV mission agent talking to a human supervisor, acting only through the listed MCP tools
// and A2A tasks), the safety rules, the tool catalogue (names, descriptions, argument and
// payload JSON Schemas, each A2A task's peer) and the reply format. The user message says
// which turn it is (k of max), the network n_t and whether it is degraded, what the supervisor
// last said, and ends with the whole context as a fenced ```json block (context_json.hpp:
// mission, airspace, initial_state, n_t, latest telemetry, the dialogue so far), which is both
// what the model reads and what `serve-model --responder scripted` rebuilds the context from.
// Retries (attempts 2 and 3) add the rejected reply and a correction that gets stricter.
#pragma once

#include <string>
#include <vector>

#include "agent/conversation/agent.hpp"
#include "agent/llm/context_json.hpp"
#include "agent/llm/llm_client.hpp"

namespace a3::agent::llm {

// What went wrong with the previous attempt, for the retry's correction.
struct FailedAttempt {
  std::string reply;                  // the model's content ("" when the call itself failed)
  std::vector<std::string> problems;  // as the reply parser names them, or the call's error
};

// How the agent acts: a JSON object in the reply's text (the paper's protocol), or native tool
// calls (OpenAI `tools`, native_prompt.hpp).
enum class ToolMode { kJson, kNative };
// "json" | "native"; throws std::invalid_argument naming the value otherwise.
ToolMode parse_tool_mode(const std::string& text);
const char* to_string(ToolMode mode);

// The agent's role and the safety rules (the start of both modes' system message).
std::string role_and_safety_text();
// The system message. attempt 3 adds the strict rules (only the JSON object, only these names,
// only the agent's own turn).
std::string system_prompt(const ToolCatalog& tools, int attempt = 1);
// The reply format, as the system message and the corrections state it.
std::string reply_format_text();
// The user message of a turn (ends with the ```json context block). Only the sentence that says
// how to answer differs between the modes.
std::string turn_prompt(const AgentContext& context, const DialogueLimits& limits = {},
                        ToolMode mode = ToolMode::kJson);
// What was wrong with the previous attempt, as both protocols' corrections begin.
std::string failure_text(const FailedAttempt& failure);
// The correction sent after a failed attempt, before attempt `attempt` (2 or 3).
std::string correction_prompt(const ToolCatalog& tools, int attempt, const FailedAttempt& failure);

// The messages for attempt `attempt` (1..3) of a turn: system, user; for a retry also the
// rejected reply (as the assistant's message, cut to a few thousand characters) and the
// correction. `failure` is required for attempts 2 and 3.
std::vector<ChatMessage> build_turn_messages(const AgentContext& context, const ToolCatalog& tools, int attempt = 1,
                                             const FailedAttempt* failure = nullptr,
                                             const DialogueLimits& limits = {});

}  // namespace a3::agent::llm
