// MCP's Streamable HTTP transport (see mcp_http.hpp).
#include "agent/mcp/mcp_http.hpp"

#include "agent/http/guarded_server.hpp"
#include "agent/mcp/jsonrpc.hpp"
#include "common/json_text.hpp"

#include <httplib.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <optional>
#include <random>
#include <stdexcept>

namespace a3::agent::mcp {
namespace {

using nlohmann::json;
constexpr auto kStopPoll = std::chrono::milliseconds(100);
constexpr size_t kMaxBodyBytes = 8u << 20;  // a JSON-RPC message to a vehicle is a few kB
constexpr int kMaxMessageDepth = 64;        // nesting of one JSON-RPC message (or batch)

bool is_final(const json& message) { return message.is_array() || jsonrpc::is_response(message); }

std::string dump(const json& message) {
  return message.dump(-1, ' ', false, json::error_handler_t::replace);
}

// The messages one POST produces (progress notifications, then its response), handed from the
// protocol's threads to the HTTP handler that writes them.
class Exchange {
 public:
  void send(const json& message) {
    {
      std::lock_guard lock(mutex_);
      outbox_.push_back(message);
    }
    ready_.notify_all();
  }
  // The next message, or nullopt when `stopping` was set first.
  std::optional<json> next(const std::atomic<bool>& stopping) {
    std::unique_lock lock(mutex_);
    while (outbox_.empty()) {
      if (stopping) return std::nullopt;
      ready_.wait_for(lock, kStopPoll);
    }
    json message = std::move(outbox_.front());
    outbox_.pop_front();
    return message;
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<json> outbox_;
};

void refuse(httplib::Response& response, int status, int code, const std::string& message) {
  response.status = status;
  response.set_content(dump(jsonrpc::make_error(nullptr, code, message)), "application/json");
}

std::string new_session_id() {
  std::random_device random;
  std::uniform_int_distribution<unsigned> byte(0, 255);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string id;
  for (int i = 0; i < 16; ++i) {
    const unsigned value = byte(random);
    id += kHex[value >> 4];
    id += kHex[value & 15];
  }
  return id;
}

bool accepts_event_stream(const httplib::Request& request) {
  if (!request.has_header("Accept")) return true;
  const std::string accept = request.get_header_value("Accept");
  return accept.find("text/event-stream") != std::string::npos || accept.find("*/*") != std::string::npos;
}

bool accepts_json(const httplib::Request& request) {
  if (!request.has_header("Accept")) return true;
  const std::string accept = request.get_header_value("Accept");
  return accept.find("application/json") != std::string::npos || accept.find("*/*") != std::string::npos ||
         accept.find("application/*") != std::string::npos;
}

// The origins the user allowed, with what an MCP client in a page sends and reads.
http::OriginPolicy browser_policy(http::OriginPolicy policy) {
  policy.cors_allow_headers = "Content-Type, Accept, Mcp-Session-Id, MCP-Protocol-Version, Last-Event-ID, Authorization";
  policy.cors_expose_headers = "Mcp-Session-Id";
  return policy;
}

// A refusal before any route (408, 411, 400, 413, 503) as a JSON-RPC error without an id.
void refuse_unrouted(const httplib::Request&, httplib::Response& response, const http::HttpRefusal& refusal) {
  refuse(response, refusal.status, refusal.status == 503 ? jsonrpc::kInternalError : jsonrpc::kInvalidRequest,
         refusal.message);
  if (refusal.retry_after_s > 0.0) {
    response.set_header("Retry-After", std::to_string(static_cast<long>(std::ceil(refusal.retry_after_s))));
  }
}

}  // namespace

McpHttpTransport::McpHttpTransport(McpRig& rig, McpServerOptions options, McpLog log)
    : rig_(rig),
      options_(std::move(options)),
      log_(std::move(log)),
      server_(std::make_unique<http::GuardedServer>(options_.http_limits, browser_policy(options_.http_origins),
                                                    kMaxBodyBytes, refuse_unrouted)) {
  server_->set_tcp_nodelay(true);
  // SO_REUSEADDR only: httplib's default SO_REUSEPORT would let a second server share the port.
  server_->set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  server_->set_keep_alive_timeout(1);
  const std::string& path = options_.http_path;
  server_->Post(path, [this](const httplib::Request& q, httplib::Response& r) { on_post(q, r); });
  server_->Delete(path, [this](const httplib::Request& q, httplib::Response& r) { on_delete(q, r); });
  server_->Get(path, [this](const httplib::Request& q, httplib::Response& r) { on_get(q, r); });
}

McpHttpTransport::~McpHttpTransport() { stop(); }

int McpHttpTransport::start() {
  if (stopping_) throw std::runtime_error("mcp http: start after stop(): the server has been stopped");
  const int port = options_.http_port == 0 ? server_->bind_to_any_port(options_.http_host)
                   : server_->bind_to_port(options_.http_host, options_.http_port) ? options_.http_port : -1;
  if (port <= 0)
    throw std::runtime_error("mcp http: cannot bind " + options_.http_host + ":" + std::to_string(options_.http_port));
  listen_thread_ = std::thread([this] {
    server_->listen_after_bind();
    listen_ended_ = true;
  });
  // httplib's stop() does nothing before listening has begun: wait for it, so stop() always ends it.
  while (!server_->is_running() && !listen_ended_) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  log_("mcp: serving Streamable HTTP on http://" + options_.http_host + ":" + std::to_string(port) + options_.http_path);
  return port;
}

void McpHttpTransport::wait() {
  std::unique_lock lock(mutex_);
  done_cv_.wait(lock, [this] { return session_over_ || stopping_; });
}

void McpHttpTransport::stop() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_.exchange(true)) return;
    if (protocol_) protocol_->shutdown();
  }
  done_cv_.notify_all();
  server_->stop();
  if (listen_thread_.joinable()) listen_thread_.join();
}

bool McpHttpTransport::admit_protocol_version(const httplib::Request& request, httplib::Response& response) {
  if (request.has_header("MCP-Protocol-Version") && !mcp_version_supported(request.get_header_value("MCP-Protocol-Version"))) {
    refuse(response, 400, jsonrpc::kInvalidRequest, "unsupported MCP-Protocol-Version '" +
           request.get_header_value("MCP-Protocol-Version") + "' (this server speaks 2025-06-18 and 2025-03-26)");
    return false;
  }
  return true;
}

std::shared_ptr<McpProtocol> McpHttpTransport::admit_session(const httplib::Request& request, httplib::Response& response) {
  std::lock_guard lock(mutex_);
  if (!request.has_header("Mcp-Session-Id")) {
    refuse(response, 400, jsonrpc::kInvalidRequest, "bad request: header Mcp-Session-Id is required after initialize");
    return nullptr;
  }
  if (session_id_.empty() || session_over_ || request.get_header_value("Mcp-Session-Id") != session_id_) {
    refuse(response, 404, jsonrpc::kInvalidRequest, "session not found: '" + request.get_header_value("Mcp-Session-Id") + "'");
    return nullptr;
  }
  return protocol_;
}

void McpHttpTransport::on_post(const httplib::Request& request, httplib::Response& response) {
  if (!admit_protocol_version(request, response)) return;
  if (request.get_header_value("Content-Type").find("application/json") == std::string::npos) {
    refuse(response, 415, jsonrpc::kInvalidRequest, "unsupported media type: POST a JSON-RPC message as application/json");
    return;
  }
  if (!accepts_json(request) && !accepts_event_stream(request)) {
    refuse(response, 406, jsonrpc::kInvalidRequest, "not acceptable: Accept must allow application/json or text/event-stream");
    return;
  }
  std::string problem;
  const auto message = common::try_parse_json_text(request.body, &problem, {kMaxBodyBytes, kMaxMessageDepth});
  if (!message) {
    refuse(response, 400, jsonrpc::kParseError, "parse error: the POST body is not valid JSON: " + problem);
    return;
  }
  if (McpProtocol::is_initialize(*message)) return open_session(*message, response);
  if (const auto protocol = admit_session(request, response))
    answer(protocol, *message, McpProtocol::wants_progress(*message) && accepts_event_stream(request), response);
}

void McpHttpTransport::open_session(const json& message, httplib::Response& response) {
  std::lock_guard lock(mutex_);
  if (!session_id_.empty()) {
    refuse(response, 409, jsonrpc::kInvalidRequest, "conflict: this rig serves one MCP session (one vehicle, one client), and it is taken");
    return;
  }
  auto protocol = std::make_shared<McpProtocol>(rig_, log_);
  json reply;
  protocol->handle(message, [&reply](const json& m) { reply = m; });
  if (reply.contains("result")) {
    session_id_ = new_session_id();
    protocol_ = protocol;
    response.set_header("Mcp-Session-Id", session_id_);
    log_("mcp: session " + session_id_ + " opened (protocol " + protocol->protocol_version() + ")");
  }
  response.set_content(dump(reply), "application/json");
}

void McpHttpTransport::answer(const std::shared_ptr<McpProtocol>& protocol, const json& message, bool stream,
                              httplib::Response& response) {
  auto exchange = std::make_shared<Exchange>();
  if (!protocol->handle(message, [exchange](const json& m) { exchange->send(m); })) {
    response.status = 202;
    return;
  }
  if (!stream) {
    std::optional<json> reply = exchange->next(stopping_);
    while (reply && !is_final(*reply)) reply = exchange->next(stopping_);
    if (!reply) return refuse(response, 503, jsonrpc::kInternalError, "the server is shutting down");
    response.set_content(dump(*reply), "application/json");
    return;
  }
  response.set_header("Cache-Control", "no-cache");
  response.set_chunked_content_provider("text/event-stream", [this, exchange](size_t, httplib::DataSink& sink) {
    std::optional<json> message = exchange->next(stopping_);
    if (!message) return false;
    const std::string event = "event: message\ndata: " + dump(*message) + "\n\n";
    if (!sink.write(event.data(), event.size())) return false;
    if (is_final(*message)) sink.done();
    return true;
  });
}

void McpHttpTransport::on_delete(const httplib::Request& request, httplib::Response& response) {
  if (!admit_protocol_version(request, response) || !admit_session(request, response)) return;
  end_session();
  response.status = 200;
}

void McpHttpTransport::end_session() {
  std::shared_ptr<McpProtocol> protocol;
  std::string session_id;
  {
    std::lock_guard lock(mutex_);
    protocol = protocol_;
    session_id = session_id_;
    session_over_ = true;
  }
  log_("mcp: the client deleted session " + session_id + "; ending the session");
  if (protocol) protocol->shutdown();
  rig_.client_closed();
  done_cv_.notify_all();
}

void McpHttpTransport::on_get(const httplib::Request& request, httplib::Response& response) {
  if (!admit_protocol_version(request, response) || !admit_session(request, response)) return;
  response.status = 405;
  response.set_header("Allow", "POST, DELETE");
}

}  // namespace a3::agent::mcp
