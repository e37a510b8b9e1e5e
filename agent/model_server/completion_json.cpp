// chat.completion objects and their streamed chunks.
#include "agent/model_server/completion_json.hpp"

namespace a3::agent::model_server {
namespace {

using nlohmann::json;

json chunk(const CompletionHeader& h, std::size_t index, const json& delta, const json& finish_reason = nullptr) {
  return {{"id", h.id},
          {"object", "chat.completion.chunk"},
          {"created", h.created},
          {"model", h.model},
          {"choices", json::array({{{"index", index}, {"delta", delta}, {"finish_reason", finish_reason}}})}};
}

std::string finish_reason_of(const ResponderReply& reply) {
  return reply.finish_reason.empty() ? "stop" : reply.finish_reason;
}

void append_tool_call_chunks(const CompletionHeader& h, std::size_t index, const std::vector<ToolCall>& calls,
                             std::vector<json>& out) {
  for (std::size_t i = 0; i < calls.size(); ++i) {
    const ToolCall& c = calls[i];
    out.push_back(chunk(h, index, {{"tool_calls", json::array({{{"index", i}, {"id", c.id}, {"type", "function"},
                                                                 {"function", {{"name", c.name}, {"arguments", ""}}}}})}}));
    for (const auto& piece : text_pieces(c.arguments)) {
      out.push_back(chunk(h, index, {{"tool_calls", json::array({{{"index", i}, {"function", {{"arguments", piece}}}}})}}));
    }
  }
}

}  // namespace

std::vector<std::string> text_pieces(const std::string& text) {
  const std::size_t piece = std::max(kPieceBytes, (text.size() + kMaxPieces - 1) / kMaxPieces);
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = std::min(text.size(), start + piece);
    while (end < text.size() && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) ++end;
    out.push_back(text.substr(start, end - start));
    start = end;
  }
  return out;
}

json message_json(const ResponderReply& reply) {
  json m = {{"role", "assistant"}, {"content", reply.content}};
  if (reply.tool_calls.empty()) return m;
  if (reply.content.empty()) m["content"] = nullptr;
  json calls = json::array();
  for (const auto& c : reply.tool_calls) {
    calls.push_back({{"id", c.id}, {"type", "function"}, {"function", {{"name", c.name}, {"arguments", c.arguments}}}});
  }
  m["tool_calls"] = calls;
  return m;
}

json completion_json(const CompletionHeader& h, const std::vector<ResponderReply>& choices, const json& usage) {
  json out_choices = json::array();
  for (std::size_t i = 0; i < choices.size(); ++i) {
    out_choices.push_back({{"index", i}, {"message", message_json(choices[i])}, {"logprobs", nullptr},
                           {"finish_reason", finish_reason_of(choices[i])}});
  }
  return {{"id", h.id}, {"object", "chat.completion"}, {"created", h.created}, {"model", h.model},
          {"choices", out_choices}, {"usage", usage}};
}

std::vector<json> completion_chunks(const CompletionHeader& h, const std::vector<ResponderReply>& choices,
                                    const json& usage) {
  std::vector<json> out;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    out.push_back(chunk(h, i, {{"role", "assistant"}, {"content", ""}}));
    for (const auto& piece : text_pieces(choices[i].content)) out.push_back(chunk(h, i, {{"content", piece}}));
    append_tool_call_chunks(h, i, choices[i].tool_calls, out);
    out.push_back(chunk(h, i, json::object(), finish_reason_of(choices[i])));
  }
  if (!usage.is_null()) {
    out.push_back({{"id", h.id}, {"object", "chat.completion.chunk"}, {"created", h.created}, {"model", h.model},
                   {"choices", json::array()}, {"usage", usage}});
  }
  return out;
}

}  // namespace a3::agent::model_server
