// An httplib::Stream over one accepted socket whose reads end at a deadline (the request head's,
// then its body's), not after a silence: a client that sends a byte every few seconds cannot keep
// a connection's thread forever. Reads are buffered (httplib reads a head byte by byte). Waits
// for reads poll in short slices so that a stopping server ends them at once. Once a read has run into its
// deadline the stream writes nothing more: the connection's owner answers 408 itself.
#pragma once

#include <httplib.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

namespace a3::agent::http {

class DeadlineStream final : public httplib::Stream {
 public:
  using Clock = std::chrono::steady_clock;

  // `stopping`: polled while waiting; true ends every wait as a failure.
  DeadlineStream(int socket, std::chrono::milliseconds write_timeout, std::function<bool()> stopping);

  // A request's head begins: reads must end by `deadline`, and the bytes read are kept (up to
  // kMaxRecordedHead) as the head's exact text, which httplib's parsed headers are not (it
  // percent-decodes header values and its get_header_value() ends at a NUL byte).
  void begin_request_head(Clock::time_point deadline);
  // Its body begins: reads must end by `deadline`; the head's text stays as it was.
  void begin_request_body(Clock::time_point deadline);
  // The head's bytes as received; empty when it was longer than kMaxRecordedHead.
  std::string_view request_head() const { return head_too_long_ ? std::string_view() : std::string_view(head_); }
  static constexpr std::size_t kMaxRecordedHead = 64u << 10;
  bool timed_out() const { return timed_out_; }
  // "request head not received within 10 s", for the 408.
  std::string timeout_message() const;
  bool has_buffered_bytes() const { return buffer_begin_ < buffer_end_; }
  // Waits until the socket is readable or `timeout` passed (or stopping); true when readable.
  bool wait_readable(std::chrono::milliseconds timeout) const;

  bool is_readable() const override;
  bool is_writable() const override;
  ssize_t read(char* ptr, size_t size) override;
  ssize_t write(const char* ptr, size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override;
  void get_local_ip_and_port(std::string& ip, int& port) const override;
  socket_t socket() const override { return socket_; }

 private:
  // Polls for `events` until `until`; true when they came. Reads also end when stopping; writes
  // do not (a stopping server still sends its last answers, bounded by the write timeout).
  bool wait_for(short events, Clock::time_point until) const;

  int socket_;
  std::chrono::milliseconds write_timeout_;
  std::function<bool()> stopping_;
  Clock::time_point read_deadline_ = Clock::time_point::max();
  Clock::time_point read_window_start_ = Clock::now();
  std::string reading_what_ = "request";
  bool recording_head_ = false;
  bool head_too_long_ = false;
  std::string head_;
  bool timed_out_ = false;
  std::array<char, 4096> buffer_{};
  std::size_t buffer_begin_ = 0;
  std::size_t buffer_end_ = 0;
};

}  // namespace a3::agent::http
