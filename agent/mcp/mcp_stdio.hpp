// MCP's stdio transport: newline-delimited UTF-8 JSON-RPC messages read from one stream and
// written to another, one message per line; writes are serialised. When the input is std::cin,
// fd 0 is read with poll() beside a wake-up pipe, so stop() ends a blocked read at once. Output
// that can no longer be written (the client died; SIGPIPE is ignored while serving) ends the
// session as EOF does.
#pragma once

#include "agent/mcp/mcp_protocol.hpp"

#include <atomic>
#include <iosfwd>
#include <string>

namespace a3::agent::mcp {

class McpStdioTransport {
 public:
  McpStdioTransport(McpRig& rig, McpLog log);
  ~McpStdioTransport();
  McpStdioTransport(const McpStdioTransport&) = delete;
  McpStdioTransport& operator=(const McpStdioTransport&) = delete;

  // Serves until EOF (then rig.client_closed()) or stop(). Blocks.
  void serve(std::istream& in, std::ostream& out);
  void stop();  // idempotent, from any thread

 private:
  bool read_line(std::istream& in, std::string& line);
  bool read_line_fd0(std::string& line);
  void wake();
  bool ending() const { return stopping_ || output_lost_; }

  McpRig& rig_;
  McpLog log_;
  std::atomic<bool> stopping_{false};
  std::atomic<bool> output_lost_{false};
  int wake_pipe_[2] = {-1, -1};
  std::string fd0_buffer_;
};

}  // namespace a3::agent::mcp
