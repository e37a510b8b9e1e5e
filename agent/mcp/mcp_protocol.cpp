// One MCP session's methods on JSON-RPC 2.0 (see mcp_protocol.hpp).
#include "agent/mcp/mcp_protocol.hpp"

#include "agent/mcp/jsonrpc.hpp"

#include <memory>
#include <optional>
#include <vector>

#include "common/json_text.hpp"

namespace a3::agent::mcp {
namespace {

using nlohmann::json;
using jsonrpc::Error;
using jsonrpc::MessageKind;

json params_of(const json& request) {
  return request.contains("params") ? request["params"] : json::object();
}

const json& require_object_params(const json& request, const json& params) {
  if (!params.is_object())
    throw Error{jsonrpc::kInvalidParams, "'" + request["method"].get<std::string>() + "': params must be an object"};
  return params;
}

std::string require_string(const json& params, const std::string& method, const std::string& field) {
  if (!params.contains(field) || !params[field].is_string())
    throw Error{jsonrpc::kInvalidParams, "'" + method + "': params." + field + " must be a string"};
  return params[field].get<std::string>();
}

json call_result_json(const McpCallResult& result) {
  std::string text = result.text.empty() ? result.structured.dump() : result.text;
  json out{{"content", json::array({json{{"type", "text"}, {"text", std::move(text)}}})},
           {"isError", result.is_error}};
  if (result.structured.is_object()) out["structuredContent"] = result.structured;
  return out;
}

// Collects a batch's responses and sends them as one array when the last one is in.
class BatchCollector {
 public:
  BatchCollector(McpSend send) : send_(std::move(send)) {}
  void expect() { ++expected_; }
  void add(const json& response) {
    std::vector<json> done;
    {
      std::lock_guard lock(mutex_);
      responses_.push_back(response);
      if (responses_.size() != expected_ || !sealed_) return;
      done.swap(responses_);
    }
    send_(json(done));
  }
  // After every member was handled: sends now when all responses are already in.
  void seal() {
    std::vector<json> done;
    {
      std::lock_guard lock(mutex_);
      sealed_ = true;
      if (responses_.size() != expected_ || expected_ == 0) return;
      done.swap(responses_);
    }
    send_(json(done));
  }

 private:
  McpSend send_;
  std::mutex mutex_;
  std::vector<json> responses_;
  size_t expected_ = 0;
  bool sealed_ = false;
};

}  // namespace

bool mcp_version_supported(const std::string& version) {
  return version == kMcpLatestVersion || version == kMcpBatchVersion;
}

McpProtocol::McpProtocol(McpRig& rig, McpLog log) : rig_(rig), log_(std::move(log)) {}

McpProtocol::~McpProtocol() { shutdown(); }

void McpProtocol::shutdown() {
  stopped_ = true;
  worker_.shutdown();
}

void McpProtocol::finish() {
  stopped_ = true;
  worker_.drain();
}

std::string McpProtocol::protocol_version() const {
  std::lock_guard lock(mutex_);
  return version_;
}

bool McpProtocol::is_initialize(const json& message) {
  return message.is_object() && message.value("method", json()) == "initialize" && message.contains("id");
}

bool McpProtocol::wants_progress(const json& message) {
  if (message.is_array()) {
    for (const auto& member : message)
      if (wants_progress(member)) return true;
    return false;
  }
  if (!message.is_object() || message.value("method", json()) != "tools/call") return false;
  const json params = message.value("params", json::object());
  return params.is_object() && params.contains("_meta") && params["_meta"].is_object() &&
         params["_meta"].contains("progressToken");
}

bool McpProtocol::handle_text(const std::string& text, const McpSend& send) {
  std::string problem;
  std::optional<json> message = common::try_parse_json_text(text, &problem);
  if (!message) {
    send(jsonrpc::make_error(nullptr, jsonrpc::kParseError, "parse error: the message is not usable JSON: " + problem));
    return true;
  }
  return handle(*message, send);
}

bool McpProtocol::handle(const json& message, const McpSend& send) {
  if (stopped_) return false;
  if (message.is_array()) return handle_batch(message, send);
  return handle_one(message, Replies{send, send});
}

bool McpProtocol::handle_batch(const json& batch, const McpSend& send) {
  const std::string version = protocol_version();
  if (batch.empty() || version != kMcpBatchVersion) {
    std::string why = batch.empty() ? "an empty batch"
                      : version.empty() ? "a batch before initialize (initialize must be sent alone)"
                                        : "batches are not part of protocol " + version;
    send(jsonrpc::make_error(nullptr, jsonrpc::kInvalidRequest, "invalid request: " + why));
    return true;
  }
  auto collector = std::make_shared<BatchCollector>(send);
  Replies replies{send, [collector](const json& response) { collector->add(response); }};
  bool any = false;
  for (const auto& member : batch) {
    if (jsonrpc::classify(member).kind == MessageKind::kRequest ||
        jsonrpc::classify(member).kind == MessageKind::kInvalid) {
      collector->expect();
      any = true;
    }
  }
  for (const auto& member : batch) handle_one(member, replies);
  collector->seal();
  return any;
}

bool McpProtocol::handle_one(const json& message, const Replies& replies) {
  const jsonrpc::Classified kind = jsonrpc::classify(message);
  switch (kind.kind) {
    case MessageKind::kInvalid:
      replies.respond(jsonrpc::make_error(kind.id, jsonrpc::kInvalidRequest, "invalid request: " + kind.problem));
      return true;
    case MessageKind::kResponse:
      log_("mcp: ignoring a response to a request this server never sent (id " + kind.id.dump() + ")");
      return false;
    case MessageKind::kNotification:
      handle_notification(message);
      return false;
    case MessageKind::kRequest:
      break;
  }
  try {
    json result = dispatch(message, replies);
    if (!result.is_null()) replies.respond(jsonrpc::make_result(kind.id, std::move(result)));
  } catch (const Error& error) {
    replies.respond(jsonrpc::make_error(kind.id, error.code, error.message));
  } catch (const std::exception& error) {
    replies.respond(jsonrpc::make_error(kind.id, jsonrpc::kInternalError,
                                        "internal error in '" + message["method"].get<std::string>() + "': " + error.what()));
  }
  return true;
}

void McpProtocol::handle_notification(const json& message) {
  const std::string method = message["method"].get<std::string>();
  if (method == "notifications/initialized") return;
  if (method == "notifications/cancelled") {
    const json params = params_of(message);
    log_("mcp: the client cancelled request " + params.value("requestId", json()).dump() +
         (params.contains("reason") ? " (" + params["reason"].dump() + ")" : std::string()) +
         "; a call already on the vehicle runs to its end");
    return;
  }
  log_("mcp: ignoring notification '" + method + "'");
}

json McpProtocol::dispatch(const json& request, const Replies& replies) {
  const std::string method = request["method"].get<std::string>();
  const json params = params_of(request);
  if (method == "ping") return json::object();
  if (method == "initialize") return on_initialize(require_object_params(request, params));
  if (protocol_version().empty())
    throw Error{jsonrpc::kInvalidRequest, "'" + method + "' before initialize: send 'initialize' first"};
  if (method == "tools/list") return json{{"tools", rig_.tools()}};
  if (method == "tools/call") return on_tools_call(request, replies);
  if (method == "resources/list") return resources_list();
  if (method == "resources/read") return on_resources_read(require_object_params(request, params));
  throw Error{jsonrpc::kMethodNotFound, "method not found: '" + method + "'"};
}

json McpProtocol::on_initialize(const json& params) {
  const std::string requested = require_string(params, "initialize", "protocolVersion");
  const std::string version = mcp_version_supported(requested) ? requested : kMcpLatestVersion;
  {
    std::lock_guard lock(mutex_);
    if (!version_.empty()) throw Error{jsonrpc::kInvalidRequest, "'initialize': the session is already initialized"};
    version_ = version;
  }
  if (version != requested) log_("mcp: client asked for protocol " + requested + "; offering " + version);
  return json{{"protocolVersion", version},
              {"capabilities", {{"tools", {{"listChanged", false}}},
                                {"resources", {{"subscribe", false}, {"listChanged", false}}}}},
              {"serverInfo", {{"name", rig_.server_name()}, {"version", rig_.server_version()}}},
              {"instructions", rig_.instructions()}};
}

bool McpProtocol::known_tool(const std::string& name) {
  std::lock_guard lock(mutex_);
  if (!tool_names_) {
    tool_names_.emplace();
    for (const auto& tool : rig_.tools()) tool_names_->insert(tool.value("name", std::string()));
  }
  return tool_names_->count(name) > 0;
}

json McpProtocol::on_tools_call(const json& request, const Replies& replies) {
  const json all_params = params_of(request);
  const json& params = require_object_params(request, all_params);
  const std::string name = require_string(params, "tools/call", "name");
  json arguments = params.value("arguments", json::object());
  if (arguments.is_null()) arguments = json::object();
  if (!arguments.is_object()) throw Error{jsonrpc::kInvalidParams, "'tools/call' " + name + ": params.arguments must be an object"};
  if (!known_tool(name)) throw Error{jsonrpc::kInvalidParams, "'tools/call': unknown tool '" + name + "'"};
  json token = nullptr;
  if (params.contains("_meta") && params["_meta"].is_object()) token = params["_meta"].value("progressToken", json());
  const json id = request["id"];
  if (!worker_.post([this, id, name, arguments, token, replies] { run_call(id, name, arguments, token, replies); }))
    throw Error{jsonrpc::kInternalError, "'tools/call' " + name + ": the server is shutting down"};
  return nullptr;
}

void McpProtocol::run_call(const json& id, const std::string& name, const json& arguments,
                           const json& progress_token, const Replies& replies) {
  std::optional<double> last_progress;
  McpProgress progress = [&](double value, std::optional<double> total, const std::string& message) {
    if (progress_token.is_null() || (last_progress && value <= *last_progress)) return;  // must rise
    last_progress = value;
    json params{{"progressToken", progress_token}, {"progress", value}};
    if (total) params["total"] = *total;
    if (!message.empty()) params["message"] = message;
    replies.notify(jsonrpc::make_notification("notifications/progress", std::move(params)));
  };
  try {
    replies.respond(jsonrpc::make_result(id, call_result_json(rig_.call_tool(name, arguments, progress))));
  } catch (const std::exception& error) {
    replies.respond(jsonrpc::make_error(id, jsonrpc::kInternalError, "internal error in tool '" + name + "': " + error.what()));
  }
}

json McpProtocol::resources_list() const {
  json list = json::array();
  for (const auto& resource : rig_.resources())
    list.push_back({{"uri", resource.uri}, {"name", resource.name},
                    {"description", resource.description}, {"mimeType", resource.mime_type}});
  return json{{"resources", list}};
}

json McpProtocol::on_resources_read(const json& params) const {
  const std::string uri = require_string(params, "resources/read", "uri");
  std::optional<std::string> text = rig_.read_resource(uri);
  if (!text) throw Error{jsonrpc::kResourceNotFound, "resource not found: '" + uri + "'"};
  std::string mime_type = "text/plain";
  for (const auto& resource : rig_.resources())
    if (resource.uri == uri) mime_type = resource.mime_type;
  return json{{"contents", json::array({json{{"uri", uri}, {"mimeType", mime_type}, {"text", *text}}})}};
}

}  // namespace a3::agent::mcp
