// MCP's Streamable HTTP transport (revision 2025-06-18) on cpp-httplib: one endpoint (POST a
// JSON-RPC message or batch; DELETE ends the session; GET answers 405, there is no
// server-initiated stream). Responses are application/json, or a text/event-stream when a
// tools/call asked for progress. One session per rig: Mcp-Session-Id is issued with the
// initialize response and required afterwards (400 without, 404 unknown). The MCP-Protocol-Version
// header must be a supported revision when present (400 otherwise). A Host that is not this
// server's address and an Origin other than its own are refused (403, DNS-rebinding protection);
// a page on an origin given in options.http_origins (--allow-origin) gets CORS headers and its
// preflights answered (http/origin_policy.hpp). Binds 127.0.0.1 unless told otherwise. Abusive
// clients are held off by http::GuardedServer (options.http_limits): a thread per connection up
// to a limit (503 beyond), head and body deadlines (408), Content-Length required (411; 400
// malformed; 413 over 8 MiB); those refusals are JSON-RPC errors without an id. A body that is
// not JSON (too deep, duplicate keys, bad UTF-8 included) is a 400 with the parse error -32700.
#pragma once

#include "agent/mcp/mcp_protocol.hpp"
#include "agent/mcp/mcp_server.hpp"

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace httplib {
struct Request;
struct Response;
}  // namespace httplib

namespace a3::agent::http {
class GuardedServer;
}  // namespace a3::agent::http

namespace a3::agent::mcp {

class McpHttpTransport {
 public:
  McpHttpTransport(McpRig& rig, McpServerOptions options, McpLog log);
  ~McpHttpTransport();  // stop()
  McpHttpTransport(const McpHttpTransport&) = delete;
  McpHttpTransport& operator=(const McpHttpTransport&) = delete;

  int start();   // the bound port; throws std::runtime_error when it cannot bind
  void wait();   // until DELETE of the session or stop()
  void stop();   // idempotent

 private:
  void on_post(const httplib::Request& request, httplib::Response& response);
  void on_delete(const httplib::Request& request, httplib::Response& response);
  void on_get(const httplib::Request& request, httplib::Response& response);
  // MCP-Protocol-Version, checked first on every method; false (and `response` filled) when
  // refused. (Host and Origin are checked before any route, by http::GuardedServer.)
  bool admit_protocol_version(const httplib::Request& request, httplib::Response& response);
  // The session named by Mcp-Session-Id; null (and `response` filled: 400 or 404) when refused.
  std::shared_ptr<McpProtocol> admit_session(const httplib::Request& request, httplib::Response& response);
  void open_session(const nlohmann::json& message, httplib::Response& response);
  void answer(const std::shared_ptr<McpProtocol>& protocol, const nlohmann::json& message,
              bool stream, httplib::Response& response);
  void end_session();

  McpRig& rig_;
  McpServerOptions options_;
  McpLog log_;
  std::unique_ptr<http::GuardedServer> server_;
  std::thread listen_thread_;
  std::mutex mutex_;
  std::condition_variable done_cv_;
  bool session_over_ = false;
  std::atomic<bool> stopping_{false};
  std::atomic<bool> listen_ended_{false};
  std::string session_id_;
  std::shared_ptr<McpProtocol> protocol_;
};

}  // namespace a3::agent::mcp
