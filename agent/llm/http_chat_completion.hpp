// The OpenAI chat-completions wire format as the LLM client speaks it: the request body
// (messages with their tool calls and tool results, tools, tool_choice, streaming), and the
// reading of a response body into content, tool calls, finish reason, model and usage. A
// response that is not what the API promises (not JSON, an error object, no choices, neither
// content nor tool calls) is reported as an error naming what is missing and how the body
// starts; nothing here throws.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "agent/llm/llm_client.hpp"

namespace a3::agent::llm {

// {"model", "messages", "temperature", "max_tokens"[, "response_format": {"type": "json_object"}]}.
nlohmann::json chat_request_body(const LlmEndpoint& endpoint, const std::vector<ChatMessage>& messages,
                                 bool with_response_format);

// Which adjustable parameters a request of `endpoint` carries, given what the server refused:
// response_format when json_output and no tools; tool_choice when set; stream_options when
// streaming; the token cap as max_tokens until refused.
SentParameters parameters_to_send(const LlmEndpoint& endpoint, const ChatRequest& request,
                                  const RefusedParameters& refused);

// The whole body: {"model", "messages", "temperature", "max_tokens" | "max_completion_tokens"
// [, "response_format"][, "tools"][, "tool_choice"][, "stream": true[, "stream_options":
// {"include_usage": true}]]}.
nlohmann::json chat_request_body(const LlmEndpoint& endpoint, const ChatRequest& request, const SentParameters& sent);

// One message as OpenAI defines it: an assistant's tool_calls ({"id", "type": "function",
// "function": {"name", "arguments"}}, content null when empty), a tool message's tool_call_id.
nlohmann::json message_json(const ChatMessage& message);

struct ChatResponse {
  std::string reply_problem;  // why the reply is a bad one although it was read (invalid UTF-8)
  std::string content;
  std::vector<ToolCall> tool_calls;
  std::string finish_reason;
  std::string model;
  LlmUsage usage;
};

// A model server's JSON text (a body, a stream chunk), parsed with common/json_text's limits.
// Text that is JSON but for invalid UTF-8 is read with each bad byte replaced by U+FFFD and
// *utf8_problem saying where: the model's reply is then a bad one to correct, not a failed call.
// nullopt (and *problem) when it is not JSON even so.
std::optional<nlohmann::json> parse_server_json(const std::string& text, std::string* problem,
                                                std::string* utf8_problem);

// Reads a 2xx body. On failure returns false and sets `error` to
// "response from <url>: <what> (body starts: <excerpt>)".
bool parse_chat_response(const std::string& body, const std::string& url, ChatResponse& out, std::string& error);

// A usage object as the client records it (total = prompt + completion when not given).
LlmUsage usage_from_json(const nlohmann::json& usage);

// The tool_calls array of a message or of a stream's assembled calls. An entry without
// function.name is a problem (returned, naming its index); arguments given as an object (some
// servers) are kept as its JSON text.
std::string read_tool_calls(const nlohmann::json& calls, std::vector<ToolCall>& out);

// The message of an OpenAI-style error body {"error": {"message": ...}} (or {"error": "..."},
// {"message": ...}), else the body's first characters; for the error text of a failed attempt.
std::string error_text_from_body(const std::string& body);

// The first `max_chars` bytes of `body` on one line (control characters escaped), "…" when cut.
std::string body_excerpt(const std::string& body, std::size_t max_chars = 200);

// Sums numbers found under the same key in both objects, recursively; keys in only one are
// copied; for anything else (strings, booleans) `into` keeps its value.
void add_usage_fields(nlohmann::json& into, const nlohmann::json& other);

}  // namespace a3::agent::llm
