// OpenAI's error object, which every non-200 answer of `a3rig serve-model` carries:
// {"error": {"message", "type", "param", "code"}} with `param` the request field at fault (or
// null) and `code` a string or null (never a number): e.g. "invalid_value", "model_not_found",
// "invalid_api_key", "rate_limit_exceeded", "unsupported_media_type".
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace a3::agent::model_server {

struct ApiError {
  int status = 400;
  std::string message;
  std::optional<std::string> param;  // the request field at fault, e.g. "tool_choice", "messages[1].role"
  std::optional<std::string> code;   // machine-readable; null when none fits
};

// "invalid_request_error" (4xx, 404 included, as OpenAI's model_not_found), "authentication_error"
// (401), "rate_limit_error" (429), "server_error" (5xx).
const char* openai_error_type(int status);
// The code sent when the error names none: 401 "invalid_api_key", 429 "rate_limit_exceeded",
// 413 "request_too_large", 415 "unsupported_media_type", else null.
std::optional<std::string> default_error_code(int status);
nlohmann::json openai_error_body(const ApiError& error);

}  // namespace a3::agent::model_server
