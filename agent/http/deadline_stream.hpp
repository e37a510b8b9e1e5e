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

namespace a3::agent::http {

class DeadlineStream final : public httplib::Stream {
 public:
  using Clock = std::chrono::steady_clock;

  // `stopping`: polled while waiting; true ends every wait as a failure.
  DeadlineStream(int socket, std::chrono::milliseconds write_timeout, std::function<bool()> stopping);

  // Reads from now on must end by `deadline`; `what` names the part being read ("request head").
  void set_read_deadline(Clock::time_point deadline, std::string what);
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
  bool timed_out_ = false;
  std::array<char, 4096> buffer_{};
  std::size_t buffer_begin_ = 0;
  std::size_t buffer_end_ = 0;
};

}  // namespace a3::agent::http
