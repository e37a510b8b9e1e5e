// Executor for the real-time runtime: one thread that waits (ppoll on its clock's schedule,
// with the LCM socket and a wake-up eventfd) and then runs due timers and delivers LCM
// messages, so a node's callbacks never run concurrently. The only place in the rig that
// blocks on wall time. Its clock is the wall clock (free-running) or a SteppedClock (lockstep:
// time moves when a grant comes, or when its ClockDriver, the pacer, moves it). Records how
// late each timer ran after its time became available (the wall schedule, or the grant), and
// counts the deadline misses (later than deadline_miss_us). A housekeeping callback may run
// every so often on wall time (the runtime publishes node statistics with it).
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "common/clock.hpp"
#include "common/clock_driver.hpp"
#include "common/executor.hpp"
#include "common/lcm_bus.hpp"
#include "common/timer_queue.hpp"

namespace a3::common {

class RealTimeExecutor final : public Executor {
 public:
  // bus may be nullptr (timers only); answers_bus, a second bus it listens to (the lockstep
  // master hears its followers' answers there), may be nullptr. All must outlive the executor.
  explicit RealTimeExecutor(const RealTimeClock& clock, LcmBus* bus = nullptr, LcmBus* answers_bus = nullptr);
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

  // Wall-clock lateness of periodic timers (a node's steps) against the time their instant
  // became available (the wall schedule, or the grant), in microseconds
  // (kept for the last max_samples events; see set_lateness_capacity).
  std::vector<double> lateness_samples_us() const;
  void set_lateness_capacity(std::size_t max_samples);
  uint64_t timers_run() const { return timers_run_.load(); }
  // Timers that ran later than deadline_miss_us after their time was available.
  void set_deadline_miss_us(double late_us) { deadline_miss_us_ = late_us; }
  uint64_t deadline_misses() const { return deadline_misses_.load(); }
  double max_lateness_us() const { return max_lateness_us_.load(); }

  // Set before run(): a driver that moves the clock (the lockstep pacer), and a callback run
  // on this thread every period_ns of wall time.
  void set_clock_driver(ClockDriver* driver) { driver_ = driver; }
  void set_housekeeping(int64_t period_ns, std::function<void()> fn);

 private:
  void wake();
  std::optional<int64_t> wait_deadline_ns(int64_t end_us) const;
  void run_due_timers();
  void run_due_steps();
  void deliver(LcmBus& bus);
  void record_lateness(double late_us);

  const RealTimeClock& clock_;
  LcmBus* bus_;
  LcmBus* answers_bus_;
  bool stepped_;  // lockstep (a SteppedClock): messages are delivered one at a time
  ClockDriver* driver_ = nullptr;
  int64_t housekeeping_period_ns_ = 0;
  int64_t next_housekeeping_ns_ = 0;
  std::function<void()> housekeeping_;
  double deadline_miss_us_ = 2000.0;
  std::atomic<uint64_t> deadline_misses_{0};
  std::atomic<double> max_lateness_us_{0.0};
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
