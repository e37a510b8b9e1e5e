// The OpenAI chat-completions wire format as the LLM client speaks it: the request body, and
// the reading of a response body into content, finish reason, model and usage. A response that
// is not what the API promises (not JSON, an error object, no choices, no content) is reported
// as an error naming what is missing and how the body starts; nothing here throws.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "agent/llm/llm_client.hpp"

namespace a3::agent::llm {

// {"model", "messages", "temperature", "max_tokens"[, "response_format": {"type": "json_object"}]}.
nlohmann::json chat_request_body(const LlmEndpoint& endpoint, const std::vector<ChatMessage>& messages,
                                 bool with_response_format);

struct ChatResponse {
  std::string content;
  std::string finish_reason;
  std::string model;
  LlmUsage usage;
};

// Reads a 2xx body. On failure returns false and sets `error` to
// "response from <url>: <what> (body starts: <excerpt>)".
bool parse_chat_response(const std::string& body, const std::string& url, ChatResponse& out, std::string& error);

// The message of an OpenAI-style error body {"error": {"message": ...}} (or {"error": "..."},
// {"message": ...}), else the body's first characters; for the error text of a failed attempt.
std::string error_text_from_body(const std::string& body);

// The first `max_chars` bytes of `body` on one line (control characters escaped), "…" when cut.
std::string body_excerpt(const std::string& body, std::size_t max_chars = 200);

// Sums numbers found under the same key in both objects, recursively; keys in only one are
// copied; for anything else (strings, booleans) `into` keeps its value.
void add_usage_fields(nlohmann::json& into, const nlohmann::json& other);

}  // namespace a3::agent::llm
