// What `a3rig serve-model` answers with. A responder turns one chat-completions request into
// one reply (content and/or tool calls, token usage, and the latency the server should take
// before answering); the server (model_server.hpp) does HTTP, latency, streaming, tool_choice,
// response_format, n and errors. Implementations:
//   corpus_responder    replays the public α³-Bench corpus: `generate` requests get the
//                       recorded episode for that scenario and seed, with its recorded
//                       gen_time_s and usage (optionally time-scaled)
//   scripted_responder  the rig's scripted policy, for closed-loop `a3rig run --agent llm`
//                       (text or tool calls), and a generic answer for any other client
//   reply_file_responder  fixed replies, in turn
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace a3::agent::model_server {

// One function call of an assistant message, as OpenAI's `tool_calls[i]` carries it.
struct ToolCall {
  std::string id;         // "" : the server numbers it ("call_<n>")
  std::string name;       // the function's name
  std::string arguments;  // a JSON text of the arguments object
};

// A request the responder cannot answer, naming the request field at fault (OpenAI's `param`).
class BadRequest : public std::invalid_argument {
 public:
  BadRequest(const std::string& message, std::string param) : std::invalid_argument(message), param_(std::move(param)) {}
  const std::string& param() const { return param_; }

 private:
  std::string param_;
};

struct ResponderReply {
  std::string content;                             // the assistant message's content ("" with tool calls: null)
  std::vector<ToolCall> tool_calls;                // only when the request offered `tools`
  nlohmann::json usage = nlohmann::json::object(); // OpenAI usage object (prompt/completion/total tokens, ...)
  std::optional<double> latency_s;                 // recorded latency to reproduce, if any
  std::string finish_reason = "stop";
};

class ModelResponder {
 public:
  virtual ~ModelResponder() = default;
  virtual std::string name() const = 0;
  // `request` is the parsed chat-completions request body, already checked by the server
  // (chat_request.hpp). Throws std::invalid_argument (or BadRequest) with a message for the
  // client (HTTP 400) when the request cannot be answered.
  virtual ResponderReply respond(const nlohmann::json& request) = 0;
};

}  // namespace a3::agent::model_server
