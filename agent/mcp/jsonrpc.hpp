// JSON-RPC 2.0 message shapes (https://www.jsonrpc.org/specification) as MCP uses them:
// classifying an incoming message, building responses, errors and notifications.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace a3::agent::mcp::jsonrpc {

inline constexpr int kParseError = -32700;
inline constexpr int kInvalidRequest = -32600;
inline constexpr int kMethodNotFound = -32601;
inline constexpr int kInvalidParams = -32602;
inline constexpr int kInternalError = -32603;
inline constexpr int kResourceNotFound = -32002;  // MCP's code for resources/read of an unknown URI

enum class MessageKind { kRequest, kNotification, kResponse, kInvalid };

struct Classified {
  MessageKind kind = MessageKind::kInvalid;
  nlohmann::json id;      // the request's or response's id (null when absent or invalid)
  std::string problem;    // why the message is invalid (kInvalid only)
};

// What one message is; never throws.
Classified classify(const nlohmann::json& message);

// True for a message that is a response to us (result or error, with an id).
bool is_response(const nlohmann::json& message);

nlohmann::json make_result(const nlohmann::json& id, nlohmann::json result);
nlohmann::json make_error(const nlohmann::json& id, int code, const std::string& message,
                          const nlohmann::json& data = nullptr);
nlohmann::json make_notification(const std::string& method, nlohmann::json params);

// A JSON-RPC error raised while handling a request; turned into an error response.
struct Error {
  int code;
  std::string message;
};

}  // namespace a3::agent::mcp::jsonrpc
