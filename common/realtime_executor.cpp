// Real-time executor: ppoll-based wait on the wall clock's schedule.
#include "common/realtime_executor.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace a3::common {

RealTimeExecutor::RealTimeExecutor(const WallClock& clock, LcmBus* bus)
    : clock_(clock), bus_(bus) {
  wake_fd_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) {
    throw std::runtime_error(std::string("RealTimeExecutor: eventfd failed: ") +
                             std::strerror(errno));
  }
}

RealTimeExecutor::~RealTimeExecutor() {
  if (wake_fd_ >= 0) ::close(wake_fd_);
}

TimerId RealTimeExecutor::schedule(int64_t first_us, int64_t period_us,
                                   std::function<void()> fn) {
  if (period_us < 0) {
    throw std::invalid_argument("RealTimeExecutor: negative period " + std::to_string(period_us));
  }
  TimerId id;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    id = queue_.add(first_us, period_us, std::move(fn));
  }
  wake();
  return id;
}

void RealTimeExecutor::cancel(TimerId id) {
  std::lock_guard<std::mutex> lock(mutex_);
  queue_.cancel(id);
}

void RealTimeExecutor::stop() {
  stop_ = true;
  wake();
}

void RealTimeExecutor::wake() {
  const uint64_t one = 1;
  [[maybe_unused]] const auto written = ::write(wake_fd_, &one, sizeof one);
}

void RealTimeExecutor::set_lateness_capacity(std::size_t max_samples) {
  std::lock_guard<std::mutex> lock(mutex_);
  lateness_capacity_ = max_samples;
  lateness_us_.clear();
  lateness_next_ = 0;
}

std::vector<double> RealTimeExecutor::lateness_samples_us() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return lateness_us_;
}

void RealTimeExecutor::run(int64_t end_us) {
  // Wake-ups as close to the deadline as the kernel allows (default slack is 50 us).
  ::prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
  pollfd fds[2] = {{wake_fd_, POLLIN, 0}, {bus_ != nullptr ? bus_->fileno() : -1, POLLIN, 0}};
  const nfds_t nfds = bus_ != nullptr ? 2 : 1;

  while (!stop_) {
    int64_t deadline_us = -1;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (auto next = queue_.next_time_us()) deadline_us = *next;
    }
    if (end_us >= 0 && (deadline_us < 0 || deadline_us > end_us)) deadline_us = end_us;

    timespec timeout{};
    timespec* timeout_ptr = nullptr;
    if (deadline_us >= 0) {
      int64_t wait_ns = clock_.mono_ns_at(deadline_us) - WallClock::monotonic_now_ns();
      if (wait_ns < 0) wait_ns = 0;
      timeout.tv_sec = wait_ns / 1'000'000'000;
      timeout.tv_nsec = wait_ns % 1'000'000'000;
      timeout_ptr = &timeout;
    }
    const int ready = ::ppoll(fds, nfds, timeout_ptr, nullptr);
    if (ready < 0 && errno != EINTR) {
      throw std::runtime_error(std::string("RealTimeExecutor: ppoll failed: ") +
                               std::strerror(errno));
    }
    if (ready > 0 && (fds[0].revents & POLLIN)) {
      uint64_t count;
      [[maybe_unused]] const auto n = ::read(wake_fd_, &count, sizeof count);
    }
    if (ready > 0 && nfds == 2 && (fds[1].revents & POLLIN)) bus_->handle_ready();

    // Run every timer due now, in schedule order.
    while (!stop_) {
      // In this order, a timer due at now_us was due by mono_now_ns: lateness is never < 0.
      const int64_t now_us = clock_.now_us();
      const int64_t mono_now_ns = WallClock::monotonic_now_ns();
      std::optional<TimerQueue::Due> due;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        due = queue_.pop_due(now_us);
        if (due && lateness_capacity_ > 0) {
          const double late_us =
              static_cast<double>(mono_now_ns - clock_.mono_ns_at(due->time_us)) * 1e-3;
          if (lateness_us_.size() < lateness_capacity_) {
            lateness_us_.push_back(late_us);
          } else {
            lateness_us_[lateness_next_] = late_us;
            lateness_next_ = (lateness_next_ + 1) % lateness_capacity_;
          }
        }
      }
      if (!due) break;
      ++timers_run_;
      (*due->fn)();
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.finish(*due);
    }
    if (end_us >= 0 && clock_.now_us() >= end_us) break;
  }
  // A stop() that came before run() started is honoured above, and consumed here.
  stop_ = false;
}

}  // namespace a3::common
