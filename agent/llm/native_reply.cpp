// A tool-calling reply as an agent turn.
#include "agent/llm/native_reply.hpp"

namespace a3::agent::llm {
namespace {

std::string excerpt(const std::string& text, std::size_t max_chars = 200) {
  return text.size() <= max_chars ? text : text.substr(0, max_chars) + "…";
}

ToolCall with_id(ToolCall call, int turn_number, std::size_t index) {
  if (call.id.empty()) call.id = "call_" + std::to_string(turn_number) + "_" + std::to_string(index);
  return call;
}

// report_turn's arguments: intent and text.
void take_report(const nlohmann::json& args, NativeReply& out) {
  out.intent = args.value("intent", std::string());
  out.text = args.value("text", std::string());
}

}  // namespace

NativeReply read_native_reply(const LlmCallResult& call, const ToolCatalog& tools, int turn_number) {
  NativeReply out;
  if (call.tool_calls.empty()) {
    out.problems.push_back("the reply called no function" +
                           (call.content.empty() ? std::string() : " (it answered with text only: \"" +
                                                                      excerpt(call.content) + "\")") +
                           "; act by calling the functions, and report_turn once with the turn's intent and text");
    return out;
  }
  for (std::size_t i = 0; i < call.tool_calls.size(); ++i) {
    const ToolCall tc = with_id(call.tool_calls[i], turn_number, i);
    const CallAsAction a = tools.action_from_call(tc.name, tc.arguments);
    if (!a.problem.empty()) {
      out.problems.push_back("tool_calls/" + std::to_string(i) + " " + a.problem);
    } else if (a.ends_turn) {
      if (!out.calls.report_call) {  // the first report counts
        take_report(a.action, out);
        out.calls.report_call = tc;
      }
    } else {
      out.actions.push_back(a.action);
      out.calls.action_calls.push_back(tc);
    }
  }
  if (!out.calls.report_call && out.problems.empty()) {
    out.intent = out.calls.action_calls.front().name;
    out.text = call.content;
  }
  if (out.intent.empty() && out.problems.empty()) out.problems.push_back("report_turn: the intent is empty");
  return out;
}

std::string native_reply_text(const LlmCallResult& call) {
  nlohmann::json calls = nlohmann::json::array();
  for (const auto& c : call.tool_calls) calls.push_back({{"name", c.name}, {"arguments", c.arguments}});
  return nlohmann::json({{"content", call.content}, {"tool_calls", calls}})
      .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace a3::agent::llm
