// What the server does to a responder's reply so that it honours the request's options
// (chat_request.hpp), whatever the responder:
//   response_format  text: as is; json_object: content that is not a JSON object is wrapped as
//                    {"text": content}; json_schema: content that satisfies the schema is kept,
//                    else replaced by an instance generated from the schema (schema_instance.hpp)
//   tool_choice      none: tool calls dropped; named X: only calls of X; required / named: when
//                    the reply has no (remaining) call, one call of the chosen / first function
//                    with arguments generated from its parameters schema; parallel_tool_calls
//                    false: the first call only; calls of functions not among `tools` dropped
//   ids              calls without an id are numbered "call_<request>_<i>"
#pragma once

#include <string>

#include "agent/model_server/chat_request.hpp"
#include "agent/model_server/model_responder.hpp"

namespace a3::agent::model_server {

std::string content_for_format(const std::string& content, const ResponseFormat& format);
// A call of `function` (a request's tools[i].function) with generated arguments.
ToolCall generated_call(const nlohmann::json& function);
void fit_tool_calls(ResponderReply& reply, const ChatOptions& options, const std::string& id_prefix);
// Both, in that order (content is left alone when the reply is only tool calls).
void shape_reply(ResponderReply& reply, const ChatOptions& options, const std::string& id_prefix);

}  // namespace a3::agent::model_server
