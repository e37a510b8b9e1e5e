// A chat-completions request as `a3rig serve-model` reads it: checked field by field (the first
// problem is an ApiError naming the field as `param`), then the options the server honours.
// Honoured: model, messages, temperature, max_tokens / max_completion_tokens, n (1..8), stream
// and stream_options.include_usage, response_format (text, json_object, json_schema), tools
// (type "function") and tool_choice ("none", "auto", "required", {"type":"function",
// "function":{"name"}}), parallel_tool_calls. Refused with 400 rather than ignored: logprobs /
// top_logprobs, audio output (`audio`, `modalities` with "audio"), the deprecated `functions` /
// `function_call`, `web_search_options`, any other tool type or response_format type, values of
// the wrong type. Other fields (seed, stop, user, penalties, metadata, ...) do not change a
// reply of these responders and are accepted.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "agent/model_server/openai_error.hpp"

namespace a3::agent::model_server {

struct ResponseFormat {
  std::string type = "text";  // "text" | "json_object" | "json_schema"
  std::string name;           // json_schema: its name
  nlohmann::json schema;      // json_schema: the schema (null: any JSON value)
};

enum class ToolChoice { kNone, kAuto, kRequired, kNamed };

struct ChatOptions {
  int n = 1;
  bool stream = false;
  bool include_usage = false;  // stream_options.include_usage
  ResponseFormat format;
  std::vector<nlohmann::json> functions;  // tools[i].function of the request, in order
  ToolChoice tool_choice = ToolChoice::kNone;  // default: kAuto when tools are given
  std::string chosen_function;                 // kNamed
  bool parallel_tool_calls = true;
};

constexpr int kMaxChoices = 8;

// The first problem of the request, or nothing when the server can honour it.
std::optional<ApiError> chat_request_error(const nlohmann::json& request);
// The options of a request chat_request_error() accepted.
ChatOptions chat_options(const nlohmann::json& request);
// The request's tools[i].function with this name, or nullptr.
const nlohmann::json* find_function(const ChatOptions& options, const std::string& name);

}  // namespace a3::agent::model_server
