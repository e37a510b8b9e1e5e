// Fitting a responder's reply to response_format and tool_choice.
#include "agent/model_server/reply_shaping.hpp"

#include "agent/model_server/schema_instance.hpp"
#include "common/json_text.hpp"

namespace a3::agent::model_server {
namespace {

using nlohmann::json;

bool allowed(const ToolCall& call, const ChatOptions& options) {
  if (find_function(options, call.name) == nullptr) return false;
  return options.tool_choice != ToolChoice::kNamed || call.name == options.chosen_function;
}

}  // namespace

std::string content_for_format(const std::string& content, const ResponseFormat& format) {
  if (format.type == "text") return content;
  const json parsed = common::try_parse_json_text(content).value_or(json(json::value_t::discarded));
  if (format.type == "json_object") {
    return parsed.is_object() ? content : json({{"text", content}}).dump();
  }
  if (!parsed.is_discarded() && schema_problems(format.schema, parsed).empty()) return content;
  return instance_of_schema(format.schema).dump();
}

ToolCall generated_call(const json& function) {
  const json parameters = function.value("parameters", json::object());
  json arguments = instance_of_schema(parameters);
  if (!arguments.is_object()) arguments = json::object();
  return {"", function["name"].get<std::string>(), arguments.dump()};
}

void fit_tool_calls(ResponderReply& reply, const ChatOptions& options, const std::string& id_prefix) {
  std::vector<ToolCall> kept;
  if (options.tool_choice != ToolChoice::kNone) {
    for (auto& call : reply.tool_calls) {
      if (allowed(call, options)) kept.push_back(std::move(call));
    }
  }
  const bool must_call = options.tool_choice == ToolChoice::kRequired || options.tool_choice == ToolChoice::kNamed;
  if (kept.empty() && must_call) {
    const std::string name = options.tool_choice == ToolChoice::kNamed ? options.chosen_function
                                                                        : options.functions.front()["name"].get<std::string>();
    kept.push_back(generated_call(*find_function(options, name)));
  }
  if (!options.parallel_tool_calls && kept.size() > 1) kept.resize(1);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (kept[i].id.empty()) kept[i].id = "call_" + id_prefix + "_" + std::to_string(i);
  }
  reply.tool_calls = std::move(kept);
  if (!reply.tool_calls.empty()) reply.finish_reason = "tool_calls";
  else if (reply.finish_reason == "tool_calls") reply.finish_reason = "stop";
}

void shape_reply(ResponderReply& reply, const ChatOptions& options, const std::string& id_prefix) {
  fit_tool_calls(reply, options, id_prefix);
  if (reply.tool_calls.empty() || !reply.content.empty()) reply.content = content_for_format(reply.content, options.format);
}

}  // namespace a3::agent::model_server
