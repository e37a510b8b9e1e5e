// What an HTTP server of the rig (serve-model, mcp --http) grants one client: connections open
// at once, and how long a request's head and body may take to arrive. A refusal is an HTTP
// status with a message, written in each server's own error shape (RefusalWriter).
#pragma once

#include <functional>
#include <string>

namespace httplib {
struct Request;
struct Response;
}  // namespace httplib

namespace a3::agent::http {

struct HttpLimits {
  int max_connections = 256;       // connections served at once, a thread each; beyond: 503
  double header_timeout_s = 10.0;  // the request line and headers must all arrive within this (408)
  double body_timeout_s = 60.0;    // the body must arrive within this once the head has (408)
  double write_timeout_s = 5.0;    // a client that reads nothing for this long is dropped
};

// Throws std::invalid_argument naming the flag (--max-connections, --header-timeout,
// --body-timeout) whose value is out of range.
void check_http_limits(const HttpLimits& limits);

struct HttpRefusal {
  int status = 0;
  std::string message;
  double retry_after_s = 0.0;  // 0: no Retry-After header
};

// Fills `response` with `refusal` in the server's error shape (and counts or logs it). The
// request is empty (no method) when the refusal came before its head was complete (408).
using RefusalWriter = std::function<void(const httplib::Request&, httplib::Response&, const HttpRefusal&)>;

}  // namespace a3::agent::http
