// Executor for the real-time runtime: one thread that waits (ppoll on the wall clock's
// schedule, with the LCM socket and a wake-up eventfd) and then runs due timers and
// delivers LCM messages, so a node's callbacks never run concurrently. The only place in
// the rig that blocks on wall time. Records how late each timer ran against its schedule.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "common/clock.hpp"
#include "common/executor.hpp"
#include "common/lcm_bus.hpp"
#include "common/timer_queue.hpp"

namespace a3::common {

class RealTimeExecutor final : public Executor {
 public:
  // bus may be nullptr (timers only). Both must outlive the executor.
  explicit RealTimeExecutor(const WallClock& clock, LcmBus* bus = nullptr);
  ~RealTimeExecutor() override;
  RealTimeExecutor(const RealTimeExecutor&) = delete;
  RealTimeExecutor& operator=(const RealTimeExecutor&) = delete;

  const Clock& clock() const override { return clock_; }
  // Thread-safe: may be called from any thread.
  TimerId schedule(int64_t first_us, int64_t period_us, std::function<void()> fn) override;
  void cancel(TimerId id) override;

  // Runs until stop() (from any thread or a callback) or until sim time end_us (< 0: none).
  // A stop() issued before run() starts makes it return at once.
  void run(int64_t end_us = -1);
  void stop();

  // Wall-clock lateness of timer callbacks against their schedule, in microseconds
  // (kept for the last max_samples events; see set_lateness_capacity).
  std::vector<double> lateness_samples_us() const;
  void set_lateness_capacity(std::size_t max_samples);
  uint64_t timers_run() const { return timers_run_.load(); }

 private:
  void wake();

  const WallClock& clock_;
  LcmBus* bus_;
  int wake_fd_ = -1;
  mutable std::mutex mutex_;
  TimerQueue queue_;
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> timers_run_{0};
  std::vector<double> lateness_us_;
  std::size_t lateness_capacity_ = 200000;
  std::size_t lateness_next_ = 0;
};

}  // namespace a3::common
