// The abuse-resistant httplib server (see guarded_server.hpp).
#include "agent/http/guarded_server.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <string>

#include "agent/http/connection_threads.hpp"
#include "agent/http/deadline_stream.hpp"
#include "agent/http/request_checks.hpp"

namespace a3::agent::http {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// The head of a request beyond the connection limit must come this soon for its 503.
constexpr double kOverLimitHeaderTimeout_s = 2.0;

// What the handlers of one connection need to know about it (set on its thread).
struct ConnectionState {
  const DeadlineStream* stream = nullptr;
  bool over_limit = false;
  int max_connections = 0;
  bool close_after_response = false;
};
thread_local ConnectionState* t_connection = nullptr;

milliseconds to_ms(double seconds) { return milliseconds(static_cast<int64_t>(seconds * 1000.0)); }

std::string reason_phrase(int status) {
  switch (status) {
    case 408: return "Request Timeout";
    case 503: return "Service Unavailable";
    default: return "Error";
  }
}

// A whole response as bytes, Connection: close.
std::string response_bytes(const httplib::Response& response) {
  std::string bytes = "HTTP/1.1 " + std::to_string(response.status) + " " + reason_phrase(response.status) + "\r\n";
  for (const auto& [name, value] : response.headers) {
    if (name != "Content-Length" && name != "Connection") bytes += name + ": " + value + "\r\n";
  }
  bytes += "Content-Length: " + std::to_string(response.body.size()) + "\r\nConnection: close\r\n\r\n";
  return bytes + response.body;
}

// Ends the connection so that the client reads the last response: our side is shut first, then
// what the client still sends (a body refused unread) is read and dropped until it pauses for
// kDrainPause, stops, or kDrainFor / kDrainBytes are spent. Closing with unread bytes would
// reset the connection, and the client could lose the response.
void close_after_last_response(socket_t sock) {
  constexpr auto kDrainPause = milliseconds(200);
  constexpr auto kDrainFor = milliseconds(2000);
  constexpr std::size_t kDrainBytes = 64u << 20;
  ::shutdown(sock, SHUT_WR);
  const auto until = Clock::now() + kDrainFor;
  static thread_local char scrap[16384];
  for (std::size_t drained = 0; drained < kDrainBytes && Clock::now() < until;) {
    pollfd fd{sock, POLLIN, 0};
    if (::poll(&fd, 1, static_cast<int>(kDrainPause.count())) <= 0) break;
    const ssize_t n = ::recv(sock, scrap, sizeof scrap, 0);
    if (n <= 0) break;
    drained += static_cast<std::size_t>(n);
  }
  ::close(sock);
}

}  // namespace

GuardedServer::GuardedServer(HttpLimits limits, OriginPolicy origins, std::size_t max_body_bytes,
                             RefusalWriter write_refusal)
    : limits_(limits), origins_(std::move(origins)), max_body_bytes_(max_body_bytes), write_refusal_(std::move(write_refusal)) {
  check_http_limits(limits_);
  check_origin_policy(origins_);
  const auto max_threads = static_cast<std::size_t>(limits_.max_connections) * 2;
  new_task_queue = [max_threads] { return new ConnectionThreads(max_threads); };
  set_payload_max_length(max_body_bytes_);
  set_pre_routing_handler([this](const httplib::Request& request, httplib::Response& response) {
    if (answered_preflight(request, response)) return HandlerResponse::Handled;
    const auto refused = refusal(request);
    if (!refused) return HandlerResponse::Unhandled;
    write_refusal_(request, response, *refused);
    response.set_header("Connection", "close");  // the body, if any, stays unread
    return HandlerResponse::Handled;
  });
  set_post_routing_handler([this](const httplib::Request& request, httplib::Response& response) {
    add_cors_headers(request, response);
  });
  set_logger([](const httplib::Request&, const httplib::Response& response) {
    if (t_connection != nullptr && response.get_header_value("Connection") == "close") {
      t_connection->close_after_response = true;
    }
  });
}

std::string_view GuardedServer::current_request_head() {
  return t_connection == nullptr ? std::string_view() : t_connection->stream->request_head();
}

bool GuardedServer::bind_to_port(const std::string& host, int port, int socket_flags) {
  if (!httplib::Server::bind_to_port(host, port, socket_flags)) return false;
  origin_check_.emplace(origins_, host, port);
  widen_listen_backlog();
  return true;
}

int GuardedServer::bind_to_any_port(const std::string& host, int socket_flags) {
  const int port = httplib::Server::bind_to_any_port(host, socket_flags);
  if (port > 0) {
    origin_check_.emplace(origins_, host, port);
    widen_listen_backlog();
  }
  return port;
}

void GuardedServer::widen_listen_backlog() {
  // listen() again on a listening socket only changes its backlog.
  ::listen(svr_sock_, SOMAXCONN);
}

std::optional<HttpRefusal> GuardedServer::refusal(const httplib::Request& request) const {
  if (t_connection != nullptr && t_connection->over_limit) {
    return HttpRefusal{503, "server busy: more than " + std::to_string(t_connection->max_connections) +
                                " connections open (--max-connections)", 1.0};
  }
  if (origin_check_) {
    auto header = [&request](const char* name) {
      return request.has_header(name) ? std::optional<std::string>(request.get_header_value(name)) : std::nullopt;
    };
    if (auto refused = origin_check_->refusal(header("Host"), header("Origin"))) return refused;
  }
  return content_length_refusal(request, max_body_bytes_);
}

bool GuardedServer::answered_preflight(const httplib::Request& request, httplib::Response& response) const {
  if (request.method != "OPTIONS" || !origin_check_ || !request.has_header("Origin") ||
      !request.has_header("Access-Control-Request-Method") ||
      !origin_check_->is_allowed_cross_origin(request.get_header_value("Origin"))) {
    return false;
  }
  response.status = 204;
  response.set_header("Access-Control-Allow-Methods", "GET, POST, DELETE, OPTIONS");
  response.set_header("Access-Control-Allow-Headers", origins_.cors_allow_headers);
  response.set_header("Access-Control-Max-Age", "600");
  return true;
}

void GuardedServer::add_cors_headers(const httplib::Request& request, httplib::Response& response) const {
  if (!origin_check_ || !request.has_header("Origin")) return;
  const std::string origin = request.get_header_value("Origin");
  if (!origin_check_->is_allowed_cross_origin(origin)) return;
  response.set_header("Access-Control-Allow-Origin", origin);
  response.set_header("Vary", "Origin");
  if (!origins_.cors_expose_headers.empty()) response.set_header("Access-Control-Expose-Headers", origins_.cors_expose_headers);
}

bool GuardedServer::process_and_close_socket(socket_t sock) {
  if (ConnectionThreads::refused_at_once()) {
    ::close(sock);
    return false;
  }
  const bool over_limit = ++open_connections_ > limits_.max_connections;
  const bool served = serve_connection(sock, over_limit);
  --open_connections_;
  close_after_last_response(sock);
  return served;
}

bool GuardedServer::serve_connection(socket_t sock, bool over_limit) {
  const auto stopping = [this] { return svr_sock_ == INVALID_SOCKET; };
  DeadlineStream stream(sock, to_ms(limits_.write_timeout_s), stopping);
  ConnectionState state{&stream, over_limit, limits_.max_connections, false};
  t_connection = &state;
  const double header_timeout_s =
      over_limit ? std::min(limits_.header_timeout_s, kOverLimitHeaderTimeout_s) : limits_.header_timeout_s;
  bool served = false;
  for (std::size_t left = keep_alive_max_count_; left > 0 && !stopping(); --left) {
    if (!stream.wait_readable(std::chrono::seconds(keep_alive_timeout_sec_))) break;
    stream.begin_request_head(Clock::now() + to_ms(header_timeout_s));
    bool client_closes = false;
    served = process_request(stream, left == 1 || over_limit, client_closes, [&](httplib::Request&) {
      stream.begin_request_body(Clock::now() + to_ms(limits_.body_timeout_s));
    });
    if (stream.timed_out()) {
      send_timeout(sock, stream.timeout_message());
      break;
    }
    if (!served || client_closes || state.close_after_response || over_limit) break;
  }
  t_connection = nullptr;
  return served;
}

void GuardedServer::send_timeout(socket_t sock, const std::string& message) const {
  httplib::Request request;
  httplib::Response response;
  write_refusal_(request, response, HttpRefusal{408, message});
  const std::string bytes = response_bytes(response);
  // A short, final write: what the socket takes without waiting.
  [[maybe_unused]] const ssize_t sent = ::send(sock, bytes.data(), bytes.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
}

}  // namespace a3::agent::http
