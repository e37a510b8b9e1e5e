// Fuzz target "model_request": one POST /v1/chat/completions as `a3rig serve-model` handles it,
// without sockets. Input: the Content-Type header's value on the first line, the body after it.
// The body is read by its media type, checked field by field, answered by the scripted
// responder (a refusal is std::invalid_argument, the server's 400), shaped to the request's
// options (response_format, tool_choice) and written as a completion and as stream chunks.
// Any other exception (the server's 500) is a finding.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "agent/model_server/chat_request.hpp"
#include "agent/model_server/completion_json.hpp"
#include "agent/model_server/reply_shaping.hpp"
#include "agent/model_server/request_body.hpp"
#include "agent/model_server/scripted_responder.hpp"
#include "fuzz/fuzz_target.hpp"
#include "fuzz/input_reader.hpp"

namespace {

namespace ms = a3::agent::model_server;

// The request a server accepted, or nothing (the error it would send).
std::optional<nlohmann::json> admitted_request(const std::string& content_type, const std::string& body) {
  const std::string media = ms::media_type(content_type);
  if (ms::form_body_error(media)) return std::nullopt;
  nlohmann::json request;
  if (ms::parse_json_body(body, media, request)) return std::nullopt;
  if (ms::chat_request_error(request)) return std::nullopt;
  return request;
}

void answer(const nlohmann::json& request) {
  const ms::ChatOptions options = ms::chat_options(request);
  static ms::ScriptedResponder responder;
  ms::ResponderReply reply;
  try {
    reply = responder.respond(request);
  } catch (const std::invalid_argument&) {
    return;  // 400
  }
  ms::shape_reply(reply, options, "0");
  const ms::CompletionHeader header{"chatcmpl-fuzz", 0, request["model"].get<std::string>()};
  const std::vector<ms::ResponderReply> choices{reply};
  (void)ms::completion_json(header, choices, nlohmann::json::object()).dump(-1, ' ', false,
                                                                           nlohmann::json::error_handler_t::replace);
  for (const auto& chunk : ms::completion_chunks(header, choices, nlohmann::json())) {
    (void)chunk.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  }
}

}  // namespace

A3_FUZZ_TARGET(model_request) {
  a3::fuzz::InputReader in(input);
  const std::string content_type = in.line();
  if (const auto request = admitted_request(content_type, in.rest())) answer(*request);
}
