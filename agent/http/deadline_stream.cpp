// The deadline-bound socket stream (see deadline_stream.hpp).
#include "agent/http/deadline_stream.hpp"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace a3::agent::http {
namespace {

using std::chrono::milliseconds;
// How often a wait looks at `stopping`.
constexpr milliseconds kStopPollSlice{100};

void address_of(const sockaddr_storage& address, socklen_t length, std::string& ip, int& port) {
  char host[NI_MAXHOST];
  char service[NI_MAXSERV];
  if (::getnameinfo(reinterpret_cast<const sockaddr*>(&address), length, host, sizeof host, service, sizeof service,
                    NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    return;
  }
  ip = host;
  port = std::atoi(service);
}

}  // namespace

DeadlineStream::DeadlineStream(int socket, milliseconds write_timeout, std::function<bool()> stopping)
    : socket_(socket), write_timeout_(write_timeout), stopping_(std::move(stopping)) {}

void DeadlineStream::begin_request_head(Clock::time_point deadline) {
  read_window_start_ = Clock::now();
  read_deadline_ = deadline;
  reading_what_ = "request head";
  recording_head_ = true;
  head_too_long_ = false;
  head_.clear();
}

void DeadlineStream::begin_request_body(Clock::time_point deadline) {
  read_window_start_ = Clock::now();
  read_deadline_ = deadline;
  reading_what_ = "request body";
  recording_head_ = false;
}

std::string DeadlineStream::timeout_message() const {
  const double window_s = std::chrono::duration<double>(read_deadline_ - read_window_start_).count();
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%g", std::round(window_s * 10.0) / 10.0);
  return reading_what_ + " not received within " + seconds + " s";
}

bool DeadlineStream::wait_for(short events, Clock::time_point until) const {
  for (;;) {
    if (events == POLLIN && stopping_ && stopping_()) return false;
    const auto now = Clock::now();
    if (now >= until) return false;
    const auto slice = std::min<milliseconds>(kStopPollSlice, std::chrono::ceil<milliseconds>(until - now));
    pollfd fd{socket_, events, 0};
    const int n = ::poll(&fd, 1, static_cast<int>(slice.count()));
    if (n < 0 && errno != EINTR) return false;
    if (n > 0) return true;  // ready, or an error / hang-up the next read or write reports
  }
}

bool DeadlineStream::wait_readable(milliseconds timeout) const {
  return has_buffered_bytes() || wait_for(POLLIN, Clock::now() + timeout);
}

bool DeadlineStream::is_readable() const { return has_buffered_bytes() || wait_for(POLLIN, read_deadline_); }

bool DeadlineStream::is_writable() const { return !timed_out_ && wait_for(POLLOUT, Clock::now() + write_timeout_); }

ssize_t DeadlineStream::read(char* ptr, size_t size) {
  if (!has_buffered_bytes()) {
    if (timed_out_) return -1;
    if (!wait_for(POLLIN, read_deadline_)) {
      timed_out_ = Clock::now() >= read_deadline_;
      return -1;
    }
    ssize_t n;
    do {
      n = ::recv(socket_, buffer_.data(), buffer_.size(), 0);
    } while (n < 0 && errno == EINTR);
    if (n <= 0) return n;
    buffer_begin_ = 0;
    buffer_end_ = static_cast<std::size_t>(n);
  }
  const std::size_t n = std::min(size, buffer_end_ - buffer_begin_);
  std::memcpy(ptr, buffer_.data() + buffer_begin_, n);
  if (recording_head_ && !head_too_long_) {
    head_too_long_ = head_.size() + n > kMaxRecordedHead;
    if (!head_too_long_) head_.append(ptr, n);
  }
  buffer_begin_ += n;
  return static_cast<ssize_t>(n);
}

ssize_t DeadlineStream::write(const char* ptr, size_t size) {
  if (timed_out_) return -1;
  std::size_t sent = 0;
  while (sent < size) {
    if (!wait_for(POLLOUT, Clock::now() + write_timeout_)) return -1;
    const ssize_t n = ::send(socket_, ptr + sent, size - sent, MSG_NOSIGNAL);
    if (n < 0 && (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK)) continue;
    if (n <= 0) return -1;
    sent += static_cast<std::size_t>(n);
  }
  return static_cast<ssize_t>(size);
}

void DeadlineStream::get_remote_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (::getpeername(socket_, reinterpret_cast<sockaddr*>(&address), &length) == 0) address_of(address, length, ip, port);
}

void DeadlineStream::get_local_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (::getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &length) == 0) address_of(address, length, ip, port);
}

}  // namespace a3::agent::http
