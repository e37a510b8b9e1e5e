// JSON-RPC 2.0 message classification and construction (see jsonrpc.hpp).
#include "agent/mcp/jsonrpc.hpp"

namespace a3::agent::mcp::jsonrpc {
namespace {

using nlohmann::json;

bool valid_id(const json& id) { return id.is_string() || id.is_number_integer() || id.is_number_unsigned(); }

Classified invalid(json id, std::string problem) {
  return Classified{MessageKind::kInvalid, std::move(id), std::move(problem)};
}

}  // namespace

Classified classify(const json& message) {
  if (!message.is_object()) return invalid(nullptr, "a JSON-RPC message must be an object, got " + std::string(message.type_name()));
  json id = message.contains("id") && valid_id(message["id"]) ? message["id"] : json(nullptr);
  if (message.value("jsonrpc", json()) != "2.0") return invalid(id, "field 'jsonrpc' must be \"2.0\"");
  if (message.contains("method")) {
    if (!message["method"].is_string()) return invalid(id, "field 'method' must be a string");
    if (message.contains("params") && !message["params"].is_object() && !message["params"].is_array())
      return invalid(id, "field 'params' must be an object or an array");
    if (!message.contains("id")) return Classified{MessageKind::kNotification, nullptr, ""};
    if (!valid_id(message["id"])) return invalid(nullptr, "field 'id' must be a string or an integer");
    return Classified{MessageKind::kRequest, id, ""};
  }
  if ((message.contains("result") || message.contains("error")) && message.contains("id"))
    return Classified{MessageKind::kResponse, id, ""};
  return invalid(id, "a message needs 'method' (request, notification) or 'result'/'error' and 'id' (response)");
}

bool is_response(const json& message) { return classify(message).kind == MessageKind::kResponse; }

json make_result(const json& id, json result) {
  return json{{"jsonrpc", "2.0"}, {"id", id}, {"result", std::move(result)}};
}

json make_error(const json& id, int code, const std::string& message, const json& data) {
  json error{{"code", code}, {"message", message}};
  if (!data.is_null()) error["data"] = data;
  return json{{"jsonrpc", "2.0"}, {"id", id}, {"error", std::move(error)}};
}

json make_notification(const std::string& method, json params) {
  return json{{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}};
}

}  // namespace a3::agent::mcp::jsonrpc
