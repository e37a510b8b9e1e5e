// Checking a chat-completions request, one function per group of fields.
#include "agent/model_server/chat_request.hpp"

#include <regex>

namespace a3::agent::model_server {
namespace {

using nlohmann::json;
using Problem = std::optional<ApiError>;

Problem bad(const std::string& param, const std::string& message, const char* code = "invalid_value") {
  return ApiError{400, message, param.empty() ? std::nullopt : std::optional<std::string>(param),
                  code ? std::optional<std::string>(code) : std::nullopt};
}

bool present(const json& request, const char* key) {
  const auto it = request.find(key);
  return it != request.end() && !it->is_null();
}

Problem content_problem(const json& m, const std::string& where, const std::string& role) {
  const auto content = m.find("content");
  if (content == m.end() || content->is_null()) {
    if (role == "assistant") return std::nullopt;
    return bad(where + ".content", where + ".content is required", nullptr);
  }
  if (!content->is_string() && !content->is_array()) {
    return bad(where + ".content", where + ".content must be a string or an array of content parts");
  }
  if (content->is_array()) {
    for (std::size_t j = 0; j < content->size(); ++j) {
      const json& part = (*content)[j];
      if (!part.is_string() && !(part.is_object() && part.contains("type") && part["type"].is_string())) {
        const std::string at = where + ".content[" + std::to_string(j) + "]";
        return bad(at, at + " must be a content part {type, ...}");
      }
    }
  }
  return std::nullopt;
}

Problem message_problem(const json& m, std::size_t i) {
  const std::string where = "messages[" + std::to_string(i) + "]";
  if (!m.is_object()) return bad(where, where + " must be an object {role, content}");
  const auto role = m.find("role");
  if (role == m.end() || !role->is_string()) return bad(where + ".role", where + ".role must be a string");
  const std::string& r = role->get_ref<const std::string&>();
  if (r != "system" && r != "user" && r != "assistant" && r != "tool" && r != "developer") {
    return bad(where + ".role", where + ".role must be one of system, user, assistant, tool, developer (got '" + r + "')");
  }
  if (r == "tool" && !(m.contains("tool_call_id") && m["tool_call_id"].is_string())) {
    return bad(where + ".tool_call_id", where + ".tool_call_id must be a string (the id of the call answered)");
  }
  return content_problem(m, where, r);
}

Problem messages_problem(const json& request) {
  const auto model = request.find("model");
  if (model == request.end()) return bad("model", "'model' is required", nullptr);
  if (!model->is_string() || model->get_ref<const std::string&>().empty()) {
    return bad("model", "'model' must be a non-empty string");
  }
  const auto messages = request.find("messages");
  if (messages == request.end()) return bad("messages", "'messages' is required", nullptr);
  if (!messages->is_array() || messages->empty()) return bad("messages", "'messages' must be a non-empty array");
  for (std::size_t i = 0; i < messages->size(); ++i) {
    if (Problem p = message_problem((*messages)[i], i)) return p;
  }
  return std::nullopt;
}

Problem sampling_problem(const json& request) {
  if (present(request, "temperature")) {
    const json& t = request["temperature"];
    if (!t.is_number() || t.get<double>() < 0.0 || t.get<double>() > 2.0) {
      return bad("temperature", "'temperature' must be a number between 0 and 2");
    }
  }
  for (const char* key : {"max_tokens", "max_completion_tokens"}) {
    if (!present(request, key)) continue;
    const json& t = request[key];
    if (!t.is_number_integer() || t.get<int64_t>() < 1) return bad(key, std::string("'") + key + "' must be an integer >= 1");
  }
  if (present(request, "n")) {
    const json& n = request["n"];
    if (!n.is_number_integer() || n.get<int64_t>() < 1 || n.get<int64_t>() > kMaxChoices) {
      return bad("n", "'n' must be an integer from 1 to " + std::to_string(kMaxChoices) + " (got " + n.dump() + ")");
    }
  }
  return std::nullopt;
}

Problem unsupported_problem(const json& request) {
  if (present(request, "logprobs") && !(request["logprobs"].is_boolean())) {
    return bad("logprobs", "'logprobs' must be a boolean");
  }
  if (present(request, "logprobs") && request["logprobs"].get<bool>()) {
    return bad("logprobs", "'logprobs': true is not supported by this server (it has no token probabilities)",
               "unsupported_value");
  }
  if (present(request, "top_logprobs")) {
    return bad("top_logprobs", "'top_logprobs' is not supported by this server (it has no token probabilities)",
               "unsupported_parameter");
  }
  for (const char* legacy : {"functions", "function_call"}) {
    if (present(request, legacy)) {
      return bad(legacy, std::string("'") + legacy + "' (the deprecated function calling) is not supported: use 'tools' "
                 "and 'tool_choice'", "unsupported_parameter");
    }
  }
  if (present(request, "web_search_options")) {
    return bad("web_search_options", "'web_search_options' is not supported by this server (no web search)",
               "unsupported_parameter");
  }
  if (present(request, "audio")) {
    return bad("audio", "'audio' output is not supported by this server (text only)", "unsupported_parameter");
  }
  if (present(request, "modalities")) {
    const json& m = request["modalities"];
    if (!m.is_array()) return bad("modalities", "'modalities' must be an array");
    for (const auto& x : m) {
      if (x != "text") {
        return bad("modalities", "'modalities' may only hold \"text\" on this server (got " + x.dump() + ")",
                   "unsupported_value");
      }
    }
  }
  return std::nullopt;
}

Problem stream_problem(const json& request) {
  const bool stream = present(request, "stream") && request["stream"].is_boolean() && request["stream"].get<bool>();
  if (present(request, "stream") && !request["stream"].is_boolean()) {
    return bad("stream", "'stream' must be a boolean (got " + request["stream"].dump() + ")");
  }
  if (!present(request, "stream_options")) return std::nullopt;
  const json& o = request["stream_options"];
  if (!stream) return bad("stream_options", "'stream_options' is only allowed when 'stream' is true");
  if (!o.is_object()) return bad("stream_options", "'stream_options' must be an object {\"include_usage\": bool}");
  if (o.contains("include_usage") && !o["include_usage"].is_boolean()) {
    return bad("stream_options.include_usage", "'stream_options.include_usage' must be a boolean");
  }
  return std::nullopt;
}

Problem response_format_problem(const json& request) {
  if (!present(request, "response_format")) return std::nullopt;
  const json& f = request["response_format"];
  if (!f.is_object() || !f.contains("type") || !f["type"].is_string()) {
    return bad("response_format", "'response_format' must be an object {\"type\": ...}");
  }
  const std::string type = f["type"];
  if (type == "text" || type == "json_object") return std::nullopt;
  if (type != "json_schema") {
    return bad("response_format.type", "'response_format.type' must be text, json_object or json_schema (got '" +
                                           type + "')");
  }
  if (!f.contains("json_schema") || !f["json_schema"].is_object()) {
    return bad("response_format.json_schema", "'response_format.json_schema' must be an object {name, schema}");
  }
  const json& s = f["json_schema"];
  if (!s.contains("name") || !s["name"].is_string()) {
    return bad("response_format.json_schema.name", "'response_format.json_schema.name' must be a string");
  }
  if (s.contains("schema") && !s["schema"].is_object() && !s["schema"].is_boolean()) {
    return bad("response_format.json_schema.schema", "'response_format.json_schema.schema' must be a JSON Schema object");
  }
  return std::nullopt;
}

Problem tool_problem(const json& tool, std::size_t i) {
  const std::string where = "tools[" + std::to_string(i) + "]";
  static const std::regex kName("^[a-zA-Z0-9_-]{1,64}$");
  if (!tool.is_object()) return bad(where, where + " must be an object {type, function}");
  if (tool.value("type", json()) != "function") {
    return bad(where + ".type", where + ".type must be \"function\" (got " + tool.value("type", json()).dump() + ")");
  }
  if (!tool.contains("function") || !tool["function"].is_object()) {
    return bad(where + ".function", where + ".function must be an object {name, description, parameters}");
  }
  const json& f = tool["function"];
  if (!f.contains("name") || !f["name"].is_string() || !std::regex_match(f["name"].get<std::string>(), kName)) {
    return bad(where + ".function.name", where + ".function.name must match ^[a-zA-Z0-9_-]{1,64}$");
  }
  if (f.contains("parameters") && !f["parameters"].is_object()) {
    return bad(where + ".function.parameters", where + ".function.parameters must be a JSON Schema object");
  }
  return std::nullopt;
}

bool offers(const json& tools, const std::string& name) {
  for (const auto& t : tools) {
    if (t["function"]["name"] == name) return true;
  }
  return false;
}

Problem tool_choice_problem(const json& request, const json& tools) {
  if (!present(request, "tool_choice")) return std::nullopt;
  const json& c = request["tool_choice"];
  if (tools.empty()) return bad("tool_choice", "'tool_choice' is only allowed when 'tools' are given");
  if (c.is_string()) {
    if (c == "none" || c == "auto" || c == "required") return std::nullopt;
    return bad("tool_choice", "'tool_choice' must be none, auto, required or {\"type\":\"function\",...} (got " +
                                  c.dump() + ")");
  }
  if (!c.is_object() || c.value("type", json()) != "function" || !c.contains("function") ||
      !c["function"].is_object() || !c["function"].contains("name") || !c["function"]["name"].is_string()) {
    return bad("tool_choice", "'tool_choice' as an object must be {\"type\":\"function\",\"function\":{\"name\":...}}");
  }
  const std::string name = c["function"]["name"];
  if (!offers(tools, name)) {
    return bad("tool_choice", "'tool_choice' names function '" + name + "', which is not among 'tools'");
  }
  return std::nullopt;
}

Problem tools_problem(const json& request) {
  const json tools = present(request, "tools") ? request["tools"] : json::array();
  if (!tools.is_array()) return bad("tools", "'tools' must be an array of {\"type\":\"function\",\"function\":{...}}");
  for (std::size_t i = 0; i < tools.size(); ++i) {
    if (Problem p = tool_problem(tools[i], i)) return p;
  }
  if (present(request, "parallel_tool_calls") && !request["parallel_tool_calls"].is_boolean()) {
    return bad("parallel_tool_calls", "'parallel_tool_calls' must be a boolean");
  }
  return tool_choice_problem(request, tools);
}

ToolChoice tool_choice_of(const json& request, std::string& chosen) {
  if (!present(request, "tool_choice")) return ToolChoice::kAuto;
  const json& c = request["tool_choice"];
  if (c.is_object()) {
    chosen = c["function"]["name"].get<std::string>();
    return ToolChoice::kNamed;
  }
  if (c == "none") return ToolChoice::kNone;
  return c == "required" ? ToolChoice::kRequired : ToolChoice::kAuto;
}

}  // namespace

std::optional<ApiError> chat_request_error(const json& request) {
  if (!request.is_object()) return bad("", "the request body must be a JSON object", nullptr);
  for (const auto& check : {messages_problem, sampling_problem, unsupported_problem, stream_problem,
                            response_format_problem, tools_problem}) {
    if (Problem p = check(request)) return p;
  }
  return std::nullopt;
}

ChatOptions chat_options(const json& request) {
  ChatOptions o;
  if (present(request, "n")) o.n = request["n"].get<int>();
  o.stream = present(request, "stream") && request["stream"].get<bool>();
  if (o.stream && present(request, "stream_options")) o.include_usage = request["stream_options"].value("include_usage", false);
  if (present(request, "response_format")) {
    const json& f = request["response_format"];
    o.format.type = f["type"].get<std::string>();
    if (o.format.type == "json_schema") {
      o.format.name = f["json_schema"]["name"].get<std::string>();
      o.format.schema = f["json_schema"].value("schema", json());
    }
  }
  if (present(request, "tools")) {
    for (const auto& t : request["tools"]) o.functions.push_back(t["function"]);
  }
  if (!o.functions.empty()) o.tool_choice = tool_choice_of(request, o.chosen_function);
  if (present(request, "parallel_tool_calls")) o.parallel_tool_calls = request["parallel_tool_calls"].get<bool>();
  return o;
}

const json* find_function(const ChatOptions& options, const std::string& name) {
  for (const auto& f : options.functions) {
    if (f["name"] == name) return &f;
  }
  return nullptr;
}

}  // namespace a3::agent::model_server
