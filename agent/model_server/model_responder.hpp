// What `a3rig serve-model` answers with. A responder turns one chat-completions request into
// one reply (content, token usage, and the latency the server should take before answering);
// the server (model_server.hpp) does HTTP, latency and errors. Implementations:
//   corpus_responder    replays the public α³-Bench corpus: `generate` requests get the
//                       recorded episode for that scenario and seed, with its recorded
//                       gen_time_s and usage (optionally time-scaled)
//   scripted_responder  the rig's scripted policy, for closed-loop `a3rig run --agent llm`
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace a3::agent::model_server {

struct ResponderReply {
  std::string content;                             // the assistant message's content
  nlohmann::json usage = nlohmann::json::object(); // OpenAI usage object (prompt/completion/total tokens, ...)
  std::optional<double> latency_s;                 // recorded latency to reproduce, if any
  std::string finish_reason = "stop";
};

class ModelResponder {
 public:
  virtual ~ModelResponder() = default;
  virtual std::string name() const = 0;
  // `request` is the parsed chat-completions request body. Throws std::invalid_argument with a
  // message for the client (HTTP 400) when the request cannot be answered.
  virtual ResponderReply respond(const nlohmann::json& request) = 0;
};

}  // namespace a3::agent::model_server
