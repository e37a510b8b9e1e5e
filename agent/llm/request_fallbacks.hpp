// Request parameters an OpenAI-compatible provider may refuse, and how the LLM client adapts:
// a 400 or 422 whose error names a parameter the request carried makes the client ask again
// without it (response_format, tool_choice, stream_options) or with max_tokens sent as
// max_completion_tokens (what OpenAI's reasoning models require), and keep doing so for later
// calls. One place decides it for every parameter, so adding one is one line here.
#pragma once

#include <string>

namespace a3::agent::llm {

// What the server refused so far.
struct RefusedParameters {
  bool response_format = false;
  bool tool_choice = false;
  bool stream_options = false;
  bool max_tokens = false;  // true: the completion cap goes as max_completion_tokens
};

// Which of those parameters a request carries (max_tokens: the cap sent under that name).
struct SentParameters {
  bool response_format = false;
  bool tool_choice = false;
  bool stream_options = false;
  bool max_tokens = false;
};

// When the answer (`http_status`, `body`) refuses a parameter that was sent: marks it in
// `refused` and returns what the client does about it ("dropping response_format",
// "sending max_completion_tokens instead of max_tokens"); else "". The refusal is read from
// OpenAI's error.param when the body has one, else from the parameter's name in the body.
std::string adapt_to_refusal(int http_status, const std::string& body, const SentParameters& sent,
                             RefusedParameters& refused);

}  // namespace a3::agent::llm
