// Adapting a chat-completions request to what the provider refused.
#include "agent/llm/request_fallbacks.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>

#include "common/json_text.hpp"

namespace a3::agent::llm {
namespace {

struct Fallback {
  const char* parameter;
  bool SentParameters::*sent;
  bool RefusedParameters::*refused;
  const char* action;
};

// In the order they are tried when one body names several.
constexpr Fallback kFallbacks[] = {
    {"response_format", &SentParameters::response_format, &RefusedParameters::response_format,
     "dropping response_format"},
    {"tool_choice", &SentParameters::tool_choice, &RefusedParameters::tool_choice, "dropping tool_choice"},
    {"stream_options", &SentParameters::stream_options, &RefusedParameters::stream_options,
     "dropping stream_options"},
    {"max_tokens", &SentParameters::max_tokens, &RefusedParameters::max_tokens,
     "sending max_completion_tokens instead of max_tokens"},
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// error.param of an OpenAI error body, "" when there is none.
std::string error_param(const std::string& body) {
  const nlohmann::json doc = common::try_parse_json_text(body).value_or(nlohmann::json());
  if (!doc.is_object() || !doc.contains("error") || !doc["error"].is_object()) return "";
  const auto& param = doc["error"].value("param", nlohmann::json());
  return param.is_string() ? param.get<std::string>() : "";
}

}  // namespace

std::string adapt_to_refusal(int http_status, const std::string& body, const SentParameters& sent,
                             RefusedParameters& refused) {
  if (http_status != 400 && http_status != 422) return "";
  const std::string param = error_param(body);
  const std::string text = lower(body);
  for (const Fallback& f : kFallbacks) {
    if (!(sent.*f.sent) || refused.*f.refused) continue;
    // "max_completion_tokens" does not contain "max_tokens": OpenAI's hint to use it is no match.
    const bool named = param.empty() ? text.find(f.parameter) != std::string::npos : param == f.parameter;
    if (named) {
      refused.*f.refused = true;
      return f.action;
    }
  }
  return "";
}

}  // namespace a3::agent::llm
