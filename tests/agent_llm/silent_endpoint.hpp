// An LLM endpoint that hangs, for the fault tests: a TCP listener on 127.0.0.1 that accepts
// every connection and reads its requests, answers the first `answered` of them with a short
// chat completion, and then never answers (the connection stays open, silent) until the test
// ends. answered = 0 is an endpoint that accepts TCP and is silent from the start.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace a3::test {

class SilentEndpoint {
 public:
  explicit SilentEndpoint(int answered = 0) : answered_(answered) {
    listener_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    if (listener_ < 0 || ::bind(listener_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
        ::listen(listener_, 16) != 0 || ::getsockname(listener_, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
      throw std::runtime_error("silent endpoint: cannot listen on 127.0.0.1");
    }
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] { serve(); });
  }
  ~SilentEndpoint() {
    done_ = true;
    thread_.join();
    for (int fd : connections_) ::close(fd);
    ::close(listener_);
  }
  SilentEndpoint(const SilentEndpoint&) = delete;
  SilentEndpoint& operator=(const SilentEndpoint&) = delete;

  std::string base_url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1"; }
  int requests() const { return requests_.load(); }

 private:
  void serve() {
    while (!done_) {
      std::vector<pollfd> fds{{listener_, POLLIN, 0}};
      for (int fd : connections_) fds.push_back({fd, POLLIN, 0});
      if (::poll(fds.data(), fds.size(), 20) <= 0) continue;
      if (fds[0].revents & POLLIN) connections_.push_back(::accept(listener_, nullptr, nullptr));
      for (std::size_t i = 1; i < fds.size(); ++i) {
        if ((fds[i].revents & (POLLIN | POLLHUP)) && !read_request(fds[i].fd)) close_connection(fds[i].fd);
      }
    }
  }
  void close_connection(int fd) {
    ::close(fd);
    connections_.erase(std::find(connections_.begin(), connections_.end(), fd));
  }
  // Counts a request when its first line comes; answers it while `answered` lasts. False when
  // the client has gone.
  bool read_request(int fd) {
    char buffer[65536];
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n <= 0) return false;
    if (std::string(buffer, static_cast<std::size_t>(n)).find("POST ") == std::string::npos) return true;
    if (requests_.fetch_add(1) >= answered_) return true;
    const std::string body =
        R"({"id":"c","object":"chat.completion","model":"m","choices":[{"index":0,"message":{"role":"assistant",)"
        R"("content":"ok"},"finish_reason":"stop"}],"usage":{"prompt_tokens":1,"completion_tokens":1,"total_tokens":2}})";
    const std::string reply = "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: " +
                              std::to_string(body.size()) + "\r\n\r\n" + body;
    [[maybe_unused]] const ssize_t w = ::write(fd, reply.data(), reply.size());
    return true;
  }

  int answered_;
  int listener_ = -1;
  int port_ = 0;
  std::atomic<bool> done_{false};
  std::atomic<int> requests_{0};
  std::vector<int> connections_;
  std::thread thread_;
};

}  // namespace a3::test
