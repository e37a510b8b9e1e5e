// Ctrl-C and SIGTERM for long-running commands: the first asks for a clean stop (the command
// polls stop_requested()), a second one ends the program at once.
#pragma once

#include <atomic>
#include <csignal>
#include <cstdlib>

namespace a3::rigs {

inline std::atomic<int>& stop_signal_count() {
  static std::atomic<int> count{0};
  return count;
}

inline void install_stop_signals() {
  auto handler = [](int) {
    if (stop_signal_count().fetch_add(1) >= 1) std::_Exit(130);
  };
  std::signal(SIGINT, handler);
  std::signal(SIGTERM, handler);
}

inline bool stop_requested() { return stop_signal_count().load() > 0; }

}  // namespace a3::rigs
