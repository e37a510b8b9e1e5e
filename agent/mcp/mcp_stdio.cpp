// MCP's stdio transport (see mcp_stdio.hpp).
#include "agent/mcp/mcp_stdio.hpp"

#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <iostream>
#include <mutex>
#include <stdexcept>

namespace a3::agent::mcp {

McpStdioTransport::McpStdioTransport(McpRig& rig, McpLog log) : rig_(rig), log_(std::move(log)) {
  if (::pipe(wake_pipe_) != 0) throw std::runtime_error("mcp stdio: cannot create the wake-up pipe");
}

McpStdioTransport::~McpStdioTransport() {
  ::close(wake_pipe_[0]);
  ::close(wake_pipe_[1]);
}

void McpStdioTransport::stop() {
  if (!stopping_.exchange(true)) wake();
}

void McpStdioTransport::wake() {
  const char byte = 1;
  [[maybe_unused]] ssize_t written = ::write(wake_pipe_[1], &byte, 1);
}

bool McpStdioTransport::read_line_fd0(std::string& line) {
  for (;;) {
    if (const auto newline = fd0_buffer_.find('\n'); newline != std::string::npos) {
      line = fd0_buffer_.substr(0, newline);
      fd0_buffer_.erase(0, newline + 1);
      return true;
    }
    pollfd fds[2] = {{0, POLLIN, 0}, {wake_pipe_[0], POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    if (ending()) return false;
    char chunk[65536];
    const ssize_t got = ::read(0, chunk, sizeof chunk);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {  // EOF: a last line without its newline still counts
      line.swap(fd0_buffer_);
      fd0_buffer_.clear();
      return !line.empty();
    }
    fd0_buffer_.append(chunk, static_cast<size_t>(got));
  }
}

bool McpStdioTransport::read_line(std::istream& in, std::string& line) {
  if (ending()) return false;
  if (&in == &std::cin) return read_line_fd0(line);
  return static_cast<bool>(std::getline(in, line)) && !ending();
}

void McpStdioTransport::serve(std::istream& in, std::ostream& out) {
  std::mutex write_mutex;
  const McpSend send = [&](const nlohmann::json& message) {
    const std::string text = message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    std::lock_guard lock(write_mutex);
    out << text << '\n';
    out.flush();
    if (!out && !output_lost_.exchange(true)) {
      log_("mcp: cannot write to the client (output closed); ending the session");
      wake();
    }
  };
  const auto previous_sigpipe = std::signal(SIGPIPE, SIG_IGN);
  McpProtocol protocol(rig_, log_);
  std::string line;
  while (read_line(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    protocol.handle_text(line, send);
  }
  if (ending()) protocol.shutdown();
  else protocol.finish();  // the client's last calls still happen
  if (!stopping_) {
    if (!output_lost_) log_("mcp: the client closed stdin; ending the session");
    rig_.client_closed();
  }
  std::signal(SIGPIPE, previous_sigpipe);
}

}  // namespace a3::agent::mcp
