// Server-sent events and the assembly of a streamed chat completion.
#include "agent/llm/sse_stream.hpp"

namespace a3::agent::llm {
namespace {

using nlohmann::json;

std::string text_of(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace

void SseLineParser::feed(std::string_view bytes, const OnData& on_data) {
  for (const char c : bytes) {
    if (after_cr_ && c == '\n') {  // the "\n" of a "\r\n" already ended the line
      after_cr_ = false;
      continue;
    }
    after_cr_ = c == '\r';
    if (c == '\r' || c == '\n') {
      end_line(on_data);
    } else {
      line_ += c;
    }
  }
}

void SseLineParser::end_line(const OnData& on_data) {
  if (line_.empty()) {  // a blank line dispatches the event
    if (has_data_) on_data(data_);
    data_.clear();
    has_data_ = false;
    return;
  }
  if (line_.rfind("data:", 0) == 0) {
    std::string_view value(line_);
    value.remove_prefix(5);
    if (!value.empty() && value.front() == ' ') value.remove_prefix(1);
    if (has_data_) data_ += '\n';
    data_.append(value);
    has_data_ = true;
  }
  line_.clear();
}

std::string ChatStreamAssembler::add(const std::string& data, bool& token) {
  token = false;
  if (data == "[DONE]") {
    done_ = true;
    return "";
  }
  std::string problem, utf8_problem;
  const json chunk = parse_server_json(data, &problem, &utf8_problem).value_or(json());
  if (!chunk.is_object()) {
    return "a stream chunk is not a JSON object" + (problem.empty() ? "" : " (" + problem + ")") +
           " (starts: " + body_excerpt(data) + ")";
  }
  if (!utf8_problem.empty() && reply_problem_.empty()) reply_problem_ = "a stream chunk is " + utf8_problem;
  if (chunk.contains("error") && !chunk["error"].is_null()) return "error in the stream: " + error_text_from_body(data);
  if (const std::string m = text_of(chunk, "model"); !m.empty()) model_ = m;
  if (chunk.contains("usage") && chunk["usage"].is_object()) usage_ = chunk["usage"];
  const json choices = chunk.value("choices", json::array());
  if (!choices.is_array() || choices.empty() || !choices[0].is_object()) return "";
  const json& choice = choices[0];
  if (const std::string f = text_of(choice, "finish_reason"); !f.empty()) finish_reason_ = f;
  if (choice.contains("delta") && choice["delta"].is_object()) add_delta(choice["delta"], token);
  return "";
}

void ChatStreamAssembler::add_delta(const json& delta, bool& token) {
  for (const char* key : {"content", "reasoning_content", "reasoning"}) {
    const std::string piece = text_of(delta, key);
    if (piece.empty()) continue;
    token = true;
    if (std::string(key) == "content") content_ += piece;
  }
  const json calls = delta.value("tool_calls", json::array());
  if (!calls.is_array()) return;
  for (const json& c : calls) {
    if (!c.is_object()) continue;
    token = true;
    const int index = c.value("index", 0);
    json& call = tool_calls_[index];
    if (call.is_null()) call = {{"id", ""}, {"function", {{"name", ""}, {"arguments", ""}}}};
    if (call["id"] == "" && !text_of(c, "id").empty()) call["id"] = text_of(c, "id");
    const json f = c.value("function", json::object());
    if (!f.is_object()) continue;
    if (call["function"]["name"] == "" && !text_of(f, "name").empty()) call["function"]["name"] = text_of(f, "name");
    call["function"]["arguments"] = call["function"]["arguments"].get<std::string>() + text_of(f, "arguments");
  }
}

std::string ChatStreamAssembler::finish(ChatResponse& out) const {
  if (!done_) return "the stream ended before data: [DONE] (cut off)";
  json calls = json::array();
  for (const auto& [index, call] : tool_calls_) calls.push_back(call);
  if (const std::string problem = read_tool_calls(calls, out.tool_calls); !problem.empty()) {
    return "streamed " + problem;
  }
  out.reply_problem = reply_problem_;
  out.content = content_;
  out.finish_reason = finish_reason_;
  out.model = model_;
  out.usage = usage_from_json(usage_);
  return "";
}

}  // namespace a3::agent::llm
