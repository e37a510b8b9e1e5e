// A streamed chat completion as it arrives: server-sent events split into their data (one small
// line parser, fed whatever bytes libcurl hands over, so a line or a JSON string may be cut
// anywhere between two calls), and the chunks of an OpenAI `chat.completion.chunk` stream
// assembled into one answer: content deltas appended, tool-call deltas merged by their index
// (id and name from the first delta that has them, arguments appended), the finish reason, the
// model and the usage chunk (stream_options.include_usage). `data: [DONE]` ends the stream; a
// stream that ends without it was cut off. Nothing here throws on the server's bytes.
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "agent/llm/http_chat_completion.hpp"

namespace a3::agent::llm {

// The data of each event (its `data:` lines joined by "\n"); other fields and comments are
// ignored. Lines end with "\n", "\r\n" or "\r".
class SseLineParser {
 public:
  using OnData = std::function<void(const std::string& data)>;
  void feed(std::string_view bytes, const OnData& on_data);

 private:
  void end_line(const OnData& on_data);

  std::string line_;
  std::string data_;
  bool has_data_ = false;
  bool after_cr_ = false;
};

class ChatStreamAssembler {
 public:
  // One event's data. Returns "" when it was read, else the problem (not JSON, an error
  // object). `token` is set when the chunk carried content, reasoning or a tool-call delta.
  std::string add(const std::string& data, bool& token);
  bool done() const { return done_; }
  // The answer so far; "" or the problem (the stream ended before [DONE], a tool call
  // without a name).
  std::string finish(ChatResponse& out) const;

 private:
  void add_delta(const nlohmann::json& delta, bool& token);

  bool done_ = false;
  std::string content_;
  std::map<int, nlohmann::json> tool_calls_;  // by index: {"id", "function": {"name", "arguments"}}
  std::string finish_reason_;
  std::string reply_problem_;  // the first chunk read only by replacing invalid UTF-8
  std::string model_;
  nlohmann::json usage_;
};

}  // namespace a3::agent::llm
