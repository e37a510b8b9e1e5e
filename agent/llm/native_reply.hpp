// Reading a tool-calling model's reply (native tool calling) into one agent turn: each function
// call of the message becomes an α³ action through the tool registry
// (ToolCatalog::action_from_call: MCP tools by name, A2A tasks as a2a_<task>), parallel calls in
// their order; the report_turn call gives the turn's intent and text. Without report_turn the
// intent is the first action's function name and the text is the message's content. A reply
// that calls no function, calls an unknown one, or passes arguments against its schema is not
// usable: every problem names the call ("tool_calls/1 navigate_to: ..."). Calls without an id
// get one ("call_<turn>_<index>") so that their results can answer them. Never throws.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "agent/llm/llm_client.hpp"
#include "agent/tool_catalog.hpp"

namespace a3::agent::llm {

// The calls a turn was made of, as the model wrote them (ids kept), for the next turns' history.
struct TurnCalls {
  std::vector<ToolCall> action_calls;  // one per action, in the actions' order
  std::optional<ToolCall> report_call;
};

struct NativeReply {
  std::string intent;
  std::string text;
  nlohmann::json actions = nlohmann::json::array();
  TurnCalls calls;
  std::vector<std::string> problems;  // empty: usable
  bool ok() const { return problems.empty(); }
};

NativeReply read_native_reply(const LlmCallResult& call, const ToolCatalog& tools, int turn_number);

// A reply as the attempt log records it: the content and the calls (name, arguments).
std::string native_reply_text(const LlmCallResult& call);

}  // namespace a3::agent::llm
