// Raw HTTP over loopback sockets for tests of the rig's HTTP servers under abuse: requests that
// an HTTP client library would refuse to send (NUL bytes in headers, bad Content-Length), and
// slow clients that trickle a request head (slowloris). Header-only; throws std::runtime_error
// naming the socket call that failed.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace a3::raw_http {

using RawClock = std::chrono::steady_clock;

inline int connect_loopback(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw std::runtime_error(std::string("socket: ") + std::strerror(errno));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw std::runtime_error("connect to 127.0.0.1:" + std::to_string(port) + ": " + why);
  }
  return fd;
}

inline bool send_text(int fd, const std::string& text) {
  return ::send(fd, text.data(), text.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(text.size());
}

struct RawResponse {
  int status = 0;         // 0: no status line came
  std::string text;       // everything received
  std::string body() const {
    const auto end = text.find("\r\n\r\n");
    return end == std::string::npos ? std::string() : text.substr(end + 4);
  }
  bool has_header(const std::string& line) const { return text.find("\r\n" + line + "\r\n") != std::string::npos; }
};

inline int status_of(const std::string& text) {
  if (text.rfind("HTTP/1.1 ", 0) != 0 || text.size() < 12) return 0;
  return std::atoi(text.substr(9, 3).c_str());
}

// Reads until the peer closes the connection or `timeout_s` passed.
inline RawResponse read_until_close(int fd, double timeout_s) {
  RawResponse response;
  const auto until = RawClock::now() + std::chrono::duration<double>(timeout_s);
  char buffer[4096];
  while (RawClock::now() < until) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 50) <= 0) continue;
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    response.text.append(buffer, static_cast<std::size_t>(n));
  }
  response.status = status_of(response.text);
  return response;
}

// One request on a new connection, sent whole; the answer read until the server closes.
inline RawResponse exchange(int port, const std::string& request, double timeout_s = 10.0) {
  const int fd = connect_loopback(port);
  send_text(fd, request);
  ::shutdown(fd, SHUT_WR);
  RawResponse response = read_until_close(fd, timeout_s);
  ::close(fd);
  return response;
}

// `count` connections that each send `request_line` and then one header line every `period`
// (never the blank line ending the head), on a thread of their own; what each receives is kept,
// and when the server closed it.
class SlowClients {
 public:
  SlowClients(int port, int count, std::chrono::milliseconds period, std::string request_line)
      : period_(period), started_(RawClock::now()) {
    for (int i = 0; i < count; ++i) {
      Client c;
      c.fd = connect_loopback(port);
      send_text(c.fd, request_line + "Host: 127.0.0.1\r\n");
      clients_.push_back(std::move(c));
    }
    thread_ = std::thread([this] { run(); });
  }
  ~SlowClients() {
    stop_ = true;
    thread_.join();
    for (const Client& c : clients_) ::close(c.fd);
  }
  SlowClients(const SlowClients&) = delete;
  SlowClients& operator=(const SlowClients&) = delete;

  int still_open() const {
    std::lock_guard lock(mutex_);
    int n = 0;
    for (const Client& c : clients_) n += !c.closed;
    return n;
  }
  // Status of what each connection received (0: nothing), and seconds from the start to its close.
  std::vector<int> statuses() const {
    std::lock_guard lock(mutex_);
    std::vector<int> out;
    for (const Client& c : clients_) out.push_back(status_of(c.received));
    return out;
  }
  double latest_close_s() const {
    std::lock_guard lock(mutex_);
    double latest = 0.0;
    for (const Client& c : clients_) latest = std::max(latest, c.closed_after_s);
    return latest;
  }
  std::string first_received() const {
    std::lock_guard lock(mutex_);
    return clients_.empty() ? std::string() : clients_.front().received;
  }

 private:
  struct Client {
    int fd = -1;
    bool closed = false;
    double closed_after_s = 0.0;
    std::string received;
    int lines_sent = 0;
  };

  void run() {
    auto next_send = RawClock::now() + period_;
    while (!stop_) {
      read_what_came();
      if (RawClock::now() >= next_send) {
        send_lines();
        next_send += period_;
      }
    }
  }
  void read_what_came() {
    std::vector<pollfd> fds;
    for (const Client& c : clients_) fds.push_back({c.closed ? -1 : c.fd, POLLIN, 0});
    if (::poll(fds.data(), fds.size(), 20) <= 0) return;
    std::lock_guard lock(mutex_);
    for (std::size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].revents == 0) continue;
      char buffer[4096];
      const ssize_t n = ::recv(clients_[i].fd, buffer, sizeof buffer, MSG_DONTWAIT);
      if (n > 0) {
        clients_[i].received.append(buffer, static_cast<std::size_t>(n));
      } else if (n == 0 || (errno != EAGAIN && errno != EINTR)) {
        mark_closed(clients_[i]);
      }
    }
  }
  void send_lines() {
    std::lock_guard lock(mutex_);
    for (Client& c : clients_) {
      if (c.closed) continue;
      if (!send_text(c.fd, "X-Slow-" + std::to_string(c.lines_sent++) + ": still typing\r\n")) mark_closed(c);
    }
  }
  void mark_closed(Client& c) {
    c.closed = true;
    c.closed_after_s = std::chrono::duration<double>(RawClock::now() - started_).count();
  }

  std::chrono::milliseconds period_;
  RawClock::time_point started_;
  mutable std::mutex mutex_;
  std::vector<Client> clients_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace a3::raw_http
