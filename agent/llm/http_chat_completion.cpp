// Request bodies and response reading for OpenAI-compatible chat completions.
#include "agent/llm/http_chat_completion.hpp"

#include <cstdio>

#include "agent/llm/json_extract.hpp"
#include "common/json_text.hpp"

namespace a3::agent::llm {
namespace {

using nlohmann::json;

// A token count as the endpoint reported it; negative, non-numeric or absurd values (beyond
// 2^53, where a count stops being exact in the episode's JSON) count as 0.
int64_t token_count(const json& usage, const char* key) {
  constexpr double kMaxTokens = 9007199254740992.0;  // 2^53
  const auto it = usage.find(key);
  if (it == usage.end() || !it->is_number()) return 0;
  const double count = it->get<double>();
  if (!(count >= 0.0 && count <= kMaxTokens)) return 0;
  return static_cast<int64_t>(count);
}

// content as a string, or as an array of text parts ({"type": "text", "text": ...} or strings).
bool content_text(const json& content, std::string& out) {
  if (content.is_string()) {
    out = content.get<std::string>();
    return true;
  }
  if (!content.is_array()) return false;
  out.clear();
  bool any = false;
  for (const auto& part : content) {
    if (part.is_string()) {
      out += part.get<std::string>();
      any = true;
    } else if (part.is_object()) {
      const auto text = part.find("text");
      if (text != part.end() && text->is_string()) {
        out += text->get<std::string>();
        any = true;
      }
    }
  }
  return any;
}

}  // namespace

json chat_request_body(const LlmEndpoint& endpoint, const std::vector<ChatMessage>& messages,
                       bool with_response_format) {
  SentParameters sent;
  sent.response_format = with_response_format;
  sent.max_tokens = true;
  LlmEndpoint plain = endpoint;
  plain.stream = false;
  return chat_request_body(plain, ChatRequest{messages}, sent);
}

SentParameters parameters_to_send(const LlmEndpoint& endpoint, const ChatRequest& request,
                                  const RefusedParameters& refused) {
  const bool has_tools = request.tools.is_array() && !request.tools.empty();
  SentParameters sent;
  sent.response_format = endpoint.json_output && !has_tools && !refused.response_format;
  sent.tool_choice = has_tools && !request.tool_choice.empty() && !refused.tool_choice;
  sent.stream_options = endpoint.stream && !refused.stream_options;
  sent.max_tokens = !refused.max_tokens;
  return sent;
}

json message_json(const ChatMessage& m) {
  json out = {{"role", m.role}, {"content", m.content}};
  if (!m.tool_calls.empty()) {
    if (m.content.empty()) out["content"] = nullptr;
    json calls = json::array();
    for (const auto& c : m.tool_calls) {
      calls.push_back({{"id", c.id}, {"type", "function"}, {"function", {{"name", c.name}, {"arguments", c.arguments}}}});
    }
    out["tool_calls"] = std::move(calls);
  }
  if (m.role == "tool") out["tool_call_id"] = m.tool_call_id;
  return out;
}

json chat_request_body(const LlmEndpoint& endpoint, const ChatRequest& request, const SentParameters& sent) {
  json body = json::object();
  body["model"] = endpoint.model;
  json list = json::array();
  for (const auto& m : request.messages) list.push_back(message_json(m));
  body["messages"] = std::move(list);
  body["temperature"] = endpoint.temperature;
  if (endpoint.max_tokens > 0) body[sent.max_tokens ? "max_tokens" : "max_completion_tokens"] = endpoint.max_tokens;
  if (sent.response_format) body["response_format"] = {{"type", "json_object"}};
  if (request.tools.is_array() && !request.tools.empty()) body["tools"] = request.tools;
  if (sent.tool_choice) body["tool_choice"] = request.tool_choice;
  if (endpoint.stream) {
    body["stream"] = true;
    if (sent.stream_options) body["stream_options"] = {{"include_usage", true}};
  }
  return body;
}

std::string read_tool_calls(const json& calls, std::vector<ToolCall>& out) {
  out.clear();
  if (calls.is_null()) return "";
  if (!calls.is_array()) return "tool_calls is not an array";
  for (std::size_t i = 0; i < calls.size(); ++i) {
    const json& c = calls[i];
    const std::string where = "tool_calls/" + std::to_string(i);
    if (!c.is_object() || !c.contains("function") || !c["function"].is_object()) return where + ": no function";
    const json& f = c["function"];
    if (!f.contains("name") || !f["name"].is_string() || f["name"].get<std::string>().empty()) {
      return where + ": no function.name";
    }
    ToolCall call;
    call.name = f["name"].get<std::string>();
    if (c.contains("id") && c["id"].is_string()) call.id = c["id"].get<std::string>();
    const json args = f.value("arguments", json());
    call.arguments = args.is_string() ? args.get<std::string>() : args.is_null() ? "" : args.dump();
    if (call.arguments.empty()) call.arguments = "{}";  // a call without arguments (some servers)
    out.push_back(std::move(call));
  }
  return "";
}

std::string body_excerpt(const std::string& body, std::size_t max_chars) {
  std::string out;
  const std::size_t n = std::min(body.size(), max_chars);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(body[i]);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (body.size() > max_chars) out += "…";
  if (body.empty()) out = "(empty)";
  return valid_utf8(out);
}

std::optional<json> parse_server_json(const std::string& text, std::string* problem, std::string* utf8_problem) {
  std::string first_problem;
  if (auto doc = common::try_parse_json_text(text, &first_problem)) return doc;
  if (first_problem.find("invalid UTF-8") != std::string::npos) {
    if (auto repaired = common::try_parse_json_text(valid_utf8(text), problem)) {
      if (utf8_problem) *utf8_problem = "not valid UTF-8 (" + first_problem + "); the invalid bytes were replaced by U+FFFD";
      return repaired;
    }
    return std::nullopt;
  }
  if (problem) *problem = first_problem;
  return std::nullopt;
}

std::string error_text_from_body(const std::string& body) {
  const json doc = parse_server_json(body, nullptr, nullptr).value_or(json());
  if (doc.is_object()) {
    const auto err = doc.find("error");
    if (err != doc.end()) {
      if (err->is_string()) return err->get<std::string>();
      if (err->is_object()) {
        const auto msg = err->find("message");
        if (msg != err->end() && msg->is_string()) return msg->get<std::string>();
      }
    }
    const auto msg = doc.find("message");
    if (msg != doc.end() && msg->is_string()) return msg->get<std::string>();
  }
  return body_excerpt(body);
}

bool parse_chat_response(const std::string& body, const std::string& url, ChatResponse& out, std::string& error) {
  auto fail = [&](const std::string& what) {
    error = "response from " + url + ": " + what + " (body starts: " + body_excerpt(body) + ")";
    return false;
  };
  std::string problem;
  const std::optional<json> parsed = parse_server_json(body, &problem, &out.reply_problem);
  if (!parsed) return fail("not JSON: " + problem);
  const json& doc = *parsed;
  if (!doc.is_object()) return fail("not a JSON object");
  if (const auto err = doc.find("error"); err != doc.end() && !err->is_null()) {
    return fail("error object: " + error_text_from_body(body));
  }
  const auto choices = doc.find("choices");
  if (choices == doc.end() || !choices->is_array() || choices->empty() || !(*choices)[0].is_object()) {
    return fail("no choices[0]");
  }
  const json& choice = (*choices)[0];
  const auto message = choice.find("message");
  if (message == choice.end() || !message->is_object()) return fail("no choices[0].message");
  if (const std::string problem = read_tool_calls(message->value("tool_calls", json()), out.tool_calls);
      !problem.empty()) {
    return fail("choices[0].message." + problem);
  }
  const auto content = message->find("content");
  const bool no_content = content == message->end() || content->is_null();
  out.content.clear();
  if (no_content ? out.tool_calls.empty() : !content_text(*content, out.content)) {
    return fail("no choices[0].message.content and no tool_calls");
  }
  out.finish_reason.clear();
  if (const auto fr = choice.find("finish_reason"); fr != choice.end() && fr->is_string()) {
    out.finish_reason = fr->get<std::string>();
  }
  out.model.clear();
  if (const auto m = doc.find("model"); m != doc.end() && m->is_string()) out.model = m->get<std::string>();
  out.usage = usage_from_json(doc.value("usage", json()));
  return true;
}

LlmUsage usage_from_json(const json& usage) {
  LlmUsage out;
  if (!usage.is_object()) return out;
  out.raw = usage;
  out.prompt_tokens = token_count(usage, "prompt_tokens");
  out.completion_tokens = token_count(usage, "completion_tokens");
  out.total_tokens = token_count(usage, "total_tokens");
  if (out.total_tokens == 0) out.total_tokens = out.prompt_tokens + out.completion_tokens;
  if (const auto cost = usage.find("cost"); cost != usage.end() && cost->is_number()) out.cost_usd = cost->get<double>();
  return out;
}

void add_usage_fields(json& into, const json& other) {
  if (!into.is_object() || !other.is_object()) return;
  for (auto it = other.begin(); it != other.end(); ++it) {
    auto mine = into.find(it.key());
    if (mine == into.end() || mine->is_null()) {
      into[it.key()] = it.value();
    } else if (mine->is_object() && it.value().is_object()) {
      add_usage_fields(*mine, it.value());
    } else if (mine->is_number() && it.value().is_number()) {
      const bool integral = (mine->is_number_integer() || mine->is_number_unsigned()) &&
                            (it.value().is_number_integer() || it.value().is_number_unsigned());
      if (integral) {
        *mine = mine->get<int64_t>() + it.value().get<int64_t>();
      } else {
        *mine = mine->get<double>() + it.value().get<double>();
      }
    }
  }
}

}  // namespace a3::agent::llm
