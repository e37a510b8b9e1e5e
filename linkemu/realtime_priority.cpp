// SCHED_FIFO for the calling thread, restored on scope exit.
#include "linkemu/realtime_priority.hpp"

#include <pthread.h>
#include <sched.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace a3::linkemu {

ScopedRealtimePriority::ScopedRealtimePriority(int priority) {
  if (priority == 0) return;
  if (priority < 1 || priority > 99) {
    throw std::invalid_argument("real-time priority must be 1..99, got " + std::to_string(priority));
  }
  sched_param old{};
  pthread_getschedparam(pthread_self(), &old_policy_, &old);
  old_priority_ = old.sched_priority;
  sched_param param{};
  param.sched_priority = priority;
  const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (error != 0) {
    throw std::runtime_error(std::string("cannot use SCHED_FIFO priority ") + std::to_string(priority) +
                             ": " + std::strerror(error) +
                             " (needs root or CAP_SYS_NICE, or a real-time limit: ulimit -r " +
                             std::to_string(priority) + ")");
  }
  changed_ = true;
}

ScopedRealtimePriority::~ScopedRealtimePriority() {
  if (!changed_) return;
  sched_param param{};
  param.sched_priority = old_priority_;
  pthread_setschedparam(pthread_self(), old_policy_, &param);
}

}  // namespace a3::linkemu
