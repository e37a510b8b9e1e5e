// Ctrl-C and SIGTERM for long-running commands: the first asks for a clean stop (the command
// polls stop_requested(), or a StopWatcher turns it into its own stop flag; an LLM call in
// flight ends within 0.1 s), a second one ends the program at once with exit status 130 and
// one line on stderr saying that nothing more is written (the episode in progress is lost).
#pragma once

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>

#include <unistd.h>

#include "common/poll_thread.hpp"

namespace a3::rigs {

inline std::atomic<int>& stop_signal_count() {
  static std::atomic<int> count{0};
  return count;
}

inline void install_stop_signals() {
  auto handler = [](int) {
    if (stop_signal_count().fetch_add(1) < 1) return;
    static constexpr char kLine[] = "a3rig: second interrupt: exiting now (status 130); nothing more is written\n";
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kLine, sizeof kLine - 1);
    std::_Exit(130);
  };
  std::signal(SIGINT, handler);
  std::signal(SIGTERM, handler);
}

inline bool stop_requested() { return stop_signal_count().load() > 0; }

// Installs the handlers and, while it lives, sets `stop` once a stop is requested (polled every
// 50 ms on a thread of its own: a signal handler may only touch the counter). It ends at once
// when it goes.
class StopWatcher {
 public:
  explicit StopWatcher(std::atomic<bool>& stop) : stop_(stop) { install_stop_signals(); }

 private:
  std::atomic<bool>& stop_;
  common::PollThread thread_{std::chrono::milliseconds(50), [this] {
                               if (stop_requested()) stop_ = true;
                               return false;
                             }};
};

}  // namespace a3::rigs
