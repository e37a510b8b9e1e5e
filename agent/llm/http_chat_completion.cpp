// Request bodies and response reading for OpenAI-compatible chat completions.
#include "agent/llm/http_chat_completion.hpp"

#include <cstdio>

namespace a3::agent::llm {
namespace {

using nlohmann::json;

int64_t token_count(const json& usage, const char* key) {
  const auto it = usage.find(key);
  if (it == usage.end() || !it->is_number()) return 0;
  if (it->is_number_integer() || it->is_number_unsigned()) return it->get<int64_t>();
  return static_cast<int64_t>(it->get<double>());
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
  json body = json::object();
  body["model"] = endpoint.model;
  json list = json::array();
  for (const auto& m : messages) list.push_back({{"role", m.role}, {"content", m.content}});
  body["messages"] = std::move(list);
  body["temperature"] = endpoint.temperature;
  if (endpoint.max_tokens > 0) body["max_tokens"] = endpoint.max_tokens;
  if (with_response_format) body["response_format"] = {{"type", "json_object"}};
  return body;
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
  return out;
}

std::string error_text_from_body(const std::string& body) {
  const json doc = json::parse(body, nullptr, false);
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
  const json doc = json::parse(body, nullptr, false);
  if (doc.is_discarded()) return fail("not JSON");
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
  const auto content = message->find("content");
  if (content == message->end() || !content_text(*content, out.content)) {
    return fail("no choices[0].message.content");
  }
  out.finish_reason.clear();
  if (const auto fr = choice.find("finish_reason"); fr != choice.end() && fr->is_string()) {
    out.finish_reason = fr->get<std::string>();
  }
  out.model.clear();
  if (const auto m = doc.find("model"); m != doc.end() && m->is_string()) out.model = m->get<std::string>();
  out.usage = LlmUsage{};
  if (const auto usage = doc.find("usage"); usage != doc.end() && usage->is_object()) {
    out.usage.raw = *usage;
    out.usage.prompt_tokens = token_count(*usage, "prompt_tokens");
    out.usage.completion_tokens = token_count(*usage, "completion_tokens");
    out.usage.total_tokens = token_count(*usage, "total_tokens");
    if (out.usage.total_tokens == 0) out.usage.total_tokens = out.usage.prompt_tokens + out.usage.completion_tokens;
    if (const auto cost = usage->find("cost"); cost != usage->end() && cost->is_number()) {
      out.usage.cost_usd = cost->get<double>();
    }
  }
  return true;
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
