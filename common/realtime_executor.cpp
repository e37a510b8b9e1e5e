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
namespace {

// Bounded, so that a steady stream of messages cannot starve the wall-clock housekeeping (the
// socket stays readable; the loop comes back for the rest).
constexpr int kMaxMessagesPerWake = 64;

}  // namespace

RealTimeExecutor::RealTimeExecutor(const RealTimeClock& clock, LcmBus* bus, LcmBus* answers_bus)
    : clock_(clock), bus_(bus), answers_bus_(answers_bus), stepped_(dynamic_cast<const SteppedClock*>(&clock) != nullptr) {
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

void RealTimeExecutor::set_housekeeping(int64_t period_ns, std::function<void()> fn) {
  housekeeping_period_ns_ = period_ns;
  housekeeping_ = std::move(fn);
  next_housekeeping_ns_ = WallClock::monotonic_now_ns() + period_ns;
}

std::optional<int64_t> RealTimeExecutor::wait_deadline_ns(int64_t end_us) const {
  std::optional<int64_t> deadline;
  const auto earliest = [&](std::optional<int64_t> t) {
    if (t && (!deadline || *t < *deadline)) deadline = t;
  };
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (auto next = queue_.next_time_us()) earliest(clock_.due_mono_ns(*next));
  }
  if (end_us >= 0) earliest(clock_.due_mono_ns(end_us));
  if (driver_ != nullptr) earliest(driver_->next_poll_mono_ns());
  if (housekeeping_) earliest(next_housekeeping_ns_);
  return deadline;
}

void RealTimeExecutor::record_lateness(double late_us) {
  if (late_us > deadline_miss_us_) ++deadline_misses_;
  if (late_us > max_lateness_us_.load(std::memory_order_relaxed)) max_lateness_us_.store(late_us);
  if (lateness_capacity_ == 0) return;
  if (lateness_us_.size() < lateness_capacity_) {
    lateness_us_.push_back(late_us);
  } else {
    lateness_us_[lateness_next_] = late_us;
    lateness_next_ = (lateness_next_ + 1) % lateness_capacity_;
  }
}

void RealTimeExecutor::run_due_timers() {
  while (!stop_) {
    // In this order, a timer due at now_us was available by mono_now_ns: lateness is never < 0.
    const int64_t now_us = clock_.now_us();
    const int64_t mono_now_ns = WallClock::monotonic_now_ns();
    std::optional<TimerQueue::Due> due;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      due = queue_.pop_due(now_us);
      // Steps (periodic timers) only: a one-shot event posted now (a received CAN frame) was
      // never due earlier.
      if (due && due->period_us > 0) {
        record_lateness(static_cast<double>(mono_now_ns - clock_.available_mono_ns(due->time_us)) * 1e-3);
      }
    }
    if (!due) return;
    ++timers_run_;
    try {
      due->fn();
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.finish(*due);  // a periodic timer keeps its callback for whoever catches this
      throw;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.finish(*due);
  }
}

void RealTimeExecutor::run_due_steps() {
  // The driver moves time one step at a time; each step's timers run before the next.
  do {
    run_due_timers();
    if (driver_ != nullptr) driver_->after_due_timers();
  } while (!stop_ && driver_ != nullptr && driver_->poll(WallClock::monotonic_now_ns()));
}

void RealTimeExecutor::deliver(LcmBus& bus) {
  if (stepped_) {
    // Lockstep: one message at a time, each followed by the timers it made due, so that the
    // timers of a grant run before the messages behind it, which were published at its time
    // (virtual time orders them so too), whatever the number one wake-up finds.
    for (int i = 0; i < kMaxMessagesPerWake && !stop_ && bus.handle_one(); ++i) run_due_steps();
  } else {
    bus.handle_ready();  // on the wall clock, time moves on its own: no grant to order
  }
}

void RealTimeExecutor::run(int64_t end_us) {
  // Wake-ups as close to the deadline as the kernel allows (default slack is 50 us).
  ::prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
  // The wake-up eventfd, then the buses there are (a negative fd is ignored by ppoll).
  pollfd fds[3] = {{wake_fd_, POLLIN, 0},
                   {bus_ != nullptr ? bus_->fileno() : -1, POLLIN, 0},
                   {answers_bus_ != nullptr ? answers_bus_->fileno() : -1, POLLIN, 0}};
  constexpr nfds_t nfds = 3;

  while (!stop_) {
    const std::optional<int64_t> deadline_ns = wait_deadline_ns(end_us);
    timespec timeout{};
    timespec* timeout_ptr = nullptr;
    if (deadline_ns) {
      int64_t wait_ns = *deadline_ns - WallClock::monotonic_now_ns();
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
    if (ready > 0 && (fds[1].revents & POLLIN)) deliver(*bus_);
    if (ready > 0 && (fds[2].revents & POLLIN)) deliver(*answers_bus_);
    run_due_steps();
    if (housekeeping_ && WallClock::monotonic_now_ns() >= next_housekeeping_ns_) {
      next_housekeeping_ns_ = WallClock::monotonic_now_ns() + housekeeping_period_ns_;
      housekeeping_();
    }
    if (end_us >= 0 && clock_.now_us() >= end_us) break;
  }
  // A stop() that came before run() started is honoured above, and consumed here.
  stop_ = false;
}

}  // namespace a3::common
