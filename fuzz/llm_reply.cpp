// Fuzz target "llm_reply": a model's reply as the llm agent reads it. The first byte picks the
// protocol: even, the json protocol (the reply's content through parse_reply); odd, native tool
// calling (a chat-completions response body through parse_chat_response, then
// read_native_reply). Both promise never to throw on the model's output.
#include <string>

#include "agent/llm/http_chat_completion.hpp"
#include "agent/llm/llm_reply.hpp"
#include "agent/llm/native_reply.hpp"
#include "agent/tool_catalog.hpp"
#include "fuzz/fuzz_target.hpp"
#include "fuzz/input_reader.hpp"

namespace {

void read_json_protocol_reply(const std::string& content) {
  const auto reply = a3::agent::llm::parse_reply(content, a3::agent::ToolCatalog::builtin());
  a3::fuzz::require(reply.ok() || !reply.problems_text().empty(), "an unusable reply without a problem");
}

void read_native_protocol_reply(const std::string& body) {
  namespace llm = a3::agent::llm;
  llm::ChatResponse response;
  std::string error;
  if (!llm::parse_chat_response(body, "http://fuzz/v1/chat/completions", response, error)) return;
  llm::LlmCallResult call;
  call.ok = true;
  call.content = response.content;
  call.tool_calls = response.tool_calls;
  call.finish_reason = response.finish_reason;
  const auto reply = llm::read_native_reply(call, a3::agent::ToolCatalog::builtin(), 3);
  a3::fuzz::require(!reply.ok() || reply.actions.is_array(), "a usable reply whose actions are not an array");
  (void)llm::native_reply_text(call);
}

}  // namespace

A3_FUZZ_TARGET(llm_reply) {
  a3::fuzz::InputReader in(input);
  const bool native = (in.byte() & 1) != 0;
  if (native) {
    read_native_protocol_reply(in.rest());
  } else {
    read_json_protocol_reply(in.rest());
  }
}
