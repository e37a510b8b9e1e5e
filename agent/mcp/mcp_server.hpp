// The MCP server behind `a3rig mcp`: the live rig (McpRig) served over the Model Context
// Protocol, revision 2025-06-18 (2025-03-26 accepted), on one of two transports: stdio
// (newline-delimited JSON-RPC on a stream pair) or Streamable HTTP (one endpoint, cpp-httplib,
// loopback by default). The protocol itself is in mcp_protocol.hpp; this class owns one
// protocol session and the transport it runs on. Diagnostics go to options.log, never stdout.
#pragma once

#include "agent/http/http_limits.hpp"
#include "agent/http/origin_policy.hpp"
#include "agent/mcp/mcp_rig.hpp"

#include <functional>
#include <iosfwd>
#include <memory>
#include <string>

namespace a3::agent::mcp {

struct McpServerOptions {
  std::string http_host = "127.0.0.1";   // loopback by default
  int http_port = 0;                     // 0: any free port
  std::string http_path = "/mcp";
  http::HttpLimits http_limits;          // connections at once, request head and body deadlines
  http::OriginPolicy http_origins;       // browser pages allowed besides the server's own; more host names
  std::function<void(const std::string&)> log;  // diagnostics (stderr by default; never stdout)
};

class McpStdioTransport;
class McpHttpTransport;

class McpServer {
 public:
  McpServer(McpRig& rig, McpServerOptions options = {});
  ~McpServer();
  McpServer(const McpServer&) = delete;
  McpServer& operator=(const McpServer&) = delete;

  // stdio transport: newline-delimited JSON-RPC messages on `in`/`out` until EOF or stop();
  // calls rig.client_closed() on EOF. Blocks. When `in` is std::cin, fd 0 is polled, so stop()
  // ends it at once; for any other stream stop() takes effect at the next line or EOF.
  void serve_stdio(std::istream& in, std::ostream& out);
  // Streamable HTTP transport on options.http_host:http_port at http_path; returns the bound
  // port; serves on threads of its own. Throws std::runtime_error when it cannot bind.
  int start_http();
  // Blocks until the HTTP session was deleted by the client (DELETE) or stop() was called.
  void wait_http();
  void stop();  // idempotent; ends serve_stdio / wait_http

 private:
  McpRig& rig_;
  McpServerOptions options_;
  std::unique_ptr<McpStdioTransport> stdio_;
  std::unique_ptr<McpHttpTransport> http_;
};

}  // namespace a3::agent::mcp
