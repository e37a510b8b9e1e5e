// The MCP server behind `a3rig mcp`: one rig, one transport (see mcp_server.hpp).
#include "agent/mcp/mcp_server.hpp"

#include "agent/mcp/mcp_http.hpp"
#include "agent/mcp/mcp_stdio.hpp"

#include <iostream>

namespace a3::agent::mcp {
namespace {

McpLog log_or_stderr(McpLog log) {
  if (log) return log;
  return [](const std::string& line) { std::cerr << line << '\n'; };
}

}  // namespace

McpServer::McpServer(McpRig& rig, McpServerOptions options) : rig_(rig), options_(std::move(options)) {
  options_.log = log_or_stderr(options_.log);
  stdio_ = std::make_unique<McpStdioTransport>(rig_, options_.log);
  http_ = std::make_unique<McpHttpTransport>(rig_, options_, options_.log);
}

McpServer::~McpServer() { stop(); }

void McpServer::serve_stdio(std::istream& in, std::ostream& out) { stdio_->serve(in, out); }

int McpServer::start_http() { return http_->start(); }

void McpServer::wait_http() { http_->wait(); }

void McpServer::stop() {
  stdio_->stop();
  http_->stop();
}

}  // namespace a3::agent::mcp
