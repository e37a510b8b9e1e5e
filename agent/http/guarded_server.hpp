// An httplib::Server that survives abusive clients; both of the rig's HTTP servers
// (serve-model, mcp --http) are one. Each connection runs on a thread of its own
// (ConnectionThreads) up to limits.max_connections, accepted from a listen backlog of SOMAXCONN; connections beyond that are answered 503
// (their head must come within 2 s), and beyond twice the limit closed unread. A request's head
// must arrive within limits.header_timeout_s and its body within limits.body_timeout_s, else the
// connection is answered 408 and closed (DeadlineStream). Before any route: 411 / 400 / 413 for
// a body without, with a malformed or with a too large Content-Length (request_checks.hpp).
// Refusals are written by the server's RefusalWriter, in its own error shape. A response with
// "Connection: close" closes the connection (httplib 0.11 would read on). Before those, the
// request's Host and Origin are checked against the address it listens on (origin_policy.hpp):
// 403 for another host name (DNS rebinding) or a page of a foreign origin; a preflight from an
// origin the policy allows is answered 204, and that origin's responses carry CORS headers.
//
// It takes httplib's pre- and post-routing handlers and logger for itself: do not set them.
#pragma once

#include <httplib.h>

#include <atomic>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "agent/http/http_limits.hpp"
#include "agent/http/origin_policy.hpp"

namespace a3::agent::http {

class GuardedServer final : public httplib::Server {
 public:
  // Throws std::invalid_argument for limits out of range (check_http_limits) or a malformed
  // origin policy (check_origin_policy).
  GuardedServer(HttpLimits limits, OriginPolicy origins, std::size_t max_body_bytes, RefusalWriter write_refusal);

  // httplib's, then the listen backlog widened from httplib's fixed 5 to SOMAXCONN: with 5, a
  // burst of connections overflows it and the client's SYN waits out a 1 s retransmission.
  bool bind_to_port(const std::string& host, int port, int socket_flags = 0);
  int bind_to_any_port(const std::string& host, int socket_flags = 0);

  int open_connections() const { return open_connections_; }

  // The exact bytes of the head of the request being handled on this thread (empty elsewhere).
  static std::string_view current_request_head();

 private:
  // httplib calls it (on a ConnectionThreads thread) for every accepted socket.
  bool process_and_close_socket(socket_t sock) override;
  bool serve_connection(socket_t sock, bool over_limit);
  void widen_listen_backlog();
  std::optional<HttpRefusal> refusal(const httplib::Request& request) const;
  // 204 with the CORS headers for a preflight from an allowed origin; false for any other request.
  bool answered_preflight(const httplib::Request& request, httplib::Response& response) const;
  void add_cors_headers(const httplib::Request& request, httplib::Response& response) const;
  // Writes the 408 for a request whose head or body came too late.
  void send_timeout(socket_t sock, const std::string& message) const;

  HttpLimits limits_;
  OriginPolicy origins_;
  std::optional<OriginCheck> origin_check_;  // set when bound (it needs the address and port)
  std::size_t max_body_bytes_;
  RefusalWriter write_refusal_;
  std::atomic<int> open_connections_{0};
};

}  // namespace a3::agent::http
