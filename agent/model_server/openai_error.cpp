// OpenAI's error object.
#include "agent/model_server/openai_error.hpp"

namespace a3::agent::model_server {

const char* openai_error_type(int status) {
  switch (status) {
    case 401: return "authentication_error";
    case 403: return "permission_error";
    case 429: return "rate_limit_error";
    default: return status >= 500 ? "server_error" : "invalid_request_error";
  }
}

std::optional<std::string> default_error_code(int status) {
  switch (status) {
    case 401: return "invalid_api_key";
    case 429: return "rate_limit_exceeded";
    case 413: return "request_too_large";
    case 415: return "unsupported_media_type";
    default: return std::nullopt;
  }
}

nlohmann::json openai_error_body(const ApiError& error) {
  const std::optional<std::string> code = error.code ? error.code : default_error_code(error.status);
  nlohmann::json e = {{"message", error.message},
                      {"type", openai_error_type(error.status)},
                      {"param", nullptr},
                      {"code", nullptr}};
  if (error.param) e["param"] = *error.param;
  if (code) e["code"] = *code;
  return {{"error", e}};
}

}  // namespace a3::agent::model_server
