// RealTimeExecutor: timers at their wall times (never early, generous bound on late),
// periodic schedule kept up to run(end_us), stop() from another thread (also before run()
// has started), cross-thread schedule waking the loop, lateness samples, LCM delivery.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "a3lcm/sim_clock_t.hpp"
#include "common/lcm_bus.hpp"
#include "common/realtime_executor.hpp"
#include "tests/common/common_test_util.hpp"

namespace a3::common {
namespace {

using std::chrono::milliseconds;
constexpr int64_t kMs = 1000;               // us per ms (simulated)
constexpr int64_t kGenerousLateNs = 500'000'000;  // 0.5 s: a loaded CI machine, not a broken loop

TEST(RealTimeExecutor, OneShotTimersRunAtTheirWallTimesInOrder) {
  const WallClock clock;
  RealTimeExecutor ex(clock);
  const int64_t t0 = clock.now_us();
  std::vector<int64_t> scheduled = {t0 + 60 * kMs, t0 + 20 * kMs, t0 + 40 * kMs};
  std::vector<std::pair<int64_t, int64_t>> ran;  // (scheduled sim time, mono ns when run)
  for (const int64_t t : scheduled) {
    ex.schedule_at(t, [&, t] { ran.emplace_back(t, WallClock::monotonic_now_ns()); });
  }
  ex.schedule_at(t0 + 60 * kMs, [&] { ex.stop(); });
  ex.run(t0 + 5'000 * kMs);  // the end is only a guard; stop() ends the run

  ASSERT_EQ(ran.size(), 3u);
  std::sort(scheduled.begin(), scheduled.end());
  for (std::size_t i = 0; i < ran.size(); ++i) {
    EXPECT_EQ(ran[i].first, scheduled[i]) << "out of order at " << i;
    const int64_t due_ns = clock.mono_ns_at(ran[i].first);
    EXPECT_GE(ran[i].second, due_ns) << "timer " << i << " ran early";
    EXPECT_LT(ran[i].second - due_ns, kGenerousLateNs) << "timer " << i << " ran very late";
  }
  EXPECT_LT(clock.now_us() - t0, 2'000 * kMs) << "stop() ended the run, not the guard";
  EXPECT_EQ(ex.timers_run(), 4u);
}

TEST(RealTimeExecutor, PeriodicTimerKeepsItsScheduleUntilRunEnd) {
  const WallClock clock(10.0);  // 10 ms simulated = 1 ms wall
  RealTimeExecutor ex(clock);
  const int64_t t0 = clock.now_us();
  std::vector<int64_t> sim_at_run;
  ex.schedule(t0 + 10 * kMs, 10 * kMs, [&] { sim_at_run.push_back(clock.now_us()); });
  const int64_t end = t0 + 500 * kMs;
  ex.run(end);
  // Every period scheduled at or before the end has run (a drifting schedule would not fit).
  ASSERT_GE(sim_at_run.size(), 50u);
  for (std::size_t k = 0; k < sim_at_run.size(); ++k) {
    EXPECT_GE(sim_at_run[k], t0 + 10 * kMs * static_cast<int64_t>(k + 1)) << "early at " << k;
  }
  EXPECT_GE(clock.now_us(), end);
  EXPECT_LT(clock.now_us() - end, 10 * kGenerousLateNs / 1000) << "run(end) overran a lot";
}

TEST(RealTimeExecutor, RunWithEndAndNoTimersReturnsAtTheEnd) {
  const WallClock clock;
  RealTimeExecutor ex(clock);
  const int64_t start_ns = WallClock::monotonic_now_ns();
  const int64_t end = clock.now_us() + 80 * kMs;
  ex.run(end);
  const int64_t waited_ns = WallClock::monotonic_now_ns() - start_ns;
  EXPECT_GE(clock.now_us(), end);
  EXPECT_GE(waited_ns, 79'000'000);
  EXPECT_LT(waited_ns, 80'000'000 + kGenerousLateNs);
  EXPECT_EQ(ex.timers_run(), 0u);
}

TEST(RealTimeExecutor, StopFromAnotherThreadEndsRun) {
  const WallClock clock;
  RealTimeExecutor ex(clock);
  std::atomic<int> ticks{0};
  ex.schedule_every(5 * kMs, [&] { ++ticks; });
  test::DeadlineThread runner([&] { ex.run(); });
  std::this_thread::sleep_for(milliseconds(60));
  ex.stop();
  EXPECT_TRUE(runner.join_within(milliseconds(2000), [&] { ex.stop(); }))
      << "run() did not return after stop()";
  EXPECT_GE(ticks.load(), 2) << "the periodic timer ran while waiting for stop()";
  const int after_stop = ticks.load();
  std::this_thread::sleep_for(milliseconds(20));
  EXPECT_EQ(ticks.load(), after_stop) << "no timer runs after run() returned";
}

TEST(RealTimeExecutor, StopIssuedBeforeRunStartsIsNotLost) {
  // A supervisor that starts a node thread and stops it at once (RealTimeNodeThread's
  // start() then stop_and_join()) must not hang, whoever gets there first.
  const WallClock clock;
  for (int i = 0; i < 200; ++i) {
    RealTimeExecutor ex(clock);
    test::DeadlineThread runner([&] { ex.run(); });
    ex.stop();
    ASSERT_TRUE(runner.join_within(milliseconds(2000), [&] { ex.stop(); }))
        << "stop() issued right after starting the thread was lost (iteration " << i << ")";
  }
}

TEST(RealTimeExecutor, CanRunAgainAfterStop) {
  const WallClock clock;
  RealTimeExecutor ex(clock);
  ex.schedule_after(5 * kMs, [&] { ex.stop(); });
  ex.run(clock.now_us() + 2'000 * kMs);
  int runs = 0;
  ex.schedule_after(5 * kMs, [&] { ++runs; });
  const int64_t end = clock.now_us() + 40 * kMs;
  ex.run(end);
  EXPECT_EQ(runs, 1) << "a stop() consumed by the first run does not end the second";
  EXPECT_GE(clock.now_us(), end);
}

TEST(RealTimeExecutor, ScheduleFromAnotherThreadWakesAnIdleLoop) {
  const WallClock clock;
  RealTimeExecutor ex(clock);
  int64_t due = 0;
  std::atomic<int64_t> ran_ns{0};
  test::DeadlineThread runner([&] { ex.run(); });  // nothing scheduled: waits indefinitely
  std::this_thread::sleep_for(milliseconds(30));
  due = clock.now_us() + 20 * kMs;
  ex.schedule_at(due, [&] {
    ran_ns = WallClock::monotonic_now_ns();
    ex.stop();
  });
  ASSERT_TRUE(runner.join_within(milliseconds(2000), [&] { ex.stop(); }))
      << "a timer scheduled from another thread did not wake the loop";
  EXPECT_GE(ran_ns.load(), clock.mono_ns_at(due));
  EXPECT_LT(ran_ns.load() - clock.mono_ns_at(due), kGenerousLateNs);
}

TEST(RealTimeExecutor, EarlierTimerFromAnotherThreadShortensTheWait) {
  const WallClock clock;
  RealTimeExecutor ex(clock);
  bool far_ran = false;
  ex.schedule_after(10'000 * kMs, [&] { far_ran = true; });  // the loop sleeps towards this
  test::DeadlineThread runner([&] { ex.run(); });
  std::this_thread::sleep_for(milliseconds(30));
  const int64_t start_ns = WallClock::monotonic_now_ns();
  ex.schedule_after(20 * kMs, [&] { ex.stop(); });
  ASSERT_TRUE(runner.join_within(milliseconds(2000), [&] { ex.stop(); }))
      << "the loop kept sleeping towards the later timer";
  EXPECT_LT(WallClock::monotonic_now_ns() - start_ns, 20'000'000 + kGenerousLateNs);
  EXPECT_FALSE(far_ran);
}

TEST(RealTimeExecutor, CancelFromAnotherThreadAndFromItsOwnCallback) {
  const WallClock clock;
  RealTimeExecutor ex(clock);
  std::atomic<bool> cancelled_ran{false};
  const TimerId victim = ex.schedule_after(60 * kMs, [&] { cancelled_ran = true; });
  int self_runs = 0;
  TimerId self = 0;
  self = ex.schedule_every(5 * kMs, [&] {
    if (++self_runs == 3) ex.cancel(self);
  });
  test::DeadlineThread runner([&] { ex.run(clock.now_us() + 120 * kMs); });
  std::this_thread::sleep_for(milliseconds(10));
  ex.cancel(victim);
  ASSERT_TRUE(runner.join_within(milliseconds(3000), [&] { ex.stop(); }));
  EXPECT_FALSE(cancelled_ran.load());
  EXPECT_EQ(self_runs, 3);
}

TEST(RealTimeExecutor, NegativePeriodIsRejected) {
  const WallClock clock;
  RealTimeExecutor ex(clock);
  EXPECT_THROW(ex.schedule(0, -5, [] {}), std::invalid_argument);
}

TEST(RealTimeExecutor, RecordsLatenessOfEveryTimerAndShowsABlockedLoop) {
  const WallClock clock;
  RealTimeExecutor ex(clock);
  int runs = 0;
  ex.schedule_every(5 * kMs, [&] {
    // The 5th callback hogs the loop for 40 ms: the next timers run late.
    if (++runs == 5) std::this_thread::sleep_for(milliseconds(40));
    if (runs == 20) ex.stop();
  });
  ex.run(clock.now_us() + 5'000 * kMs);
  const std::vector<double> late_us = ex.lateness_samples_us();
  ASSERT_EQ(runs, 20);
  ASSERT_EQ(late_us.size(), 20u) << "one sample per timer run";
  EXPECT_EQ(ex.timers_run(), 20u);
  for (std::size_t i = 0; i < late_us.size(); ++i) {
    EXPECT_GE(late_us[i], 0.0) << "sample " << i << ": a timer never runs before its time";
  }
  EXPECT_LT(late_us[0], static_cast<double>(kGenerousLateNs) * 1e-3);
  // The timer after the hog was due 5 ms later and ran after 40 ms: >= 35 ms late.
  EXPECT_GE(late_us[5], 30'000.0) << "the blocked loop shows up as lateness";
}

TEST(RealTimeExecutor, LatenessCapacityBoundsTheSamples) {
  const WallClock clock(100.0);  // 1 ms simulated = 10 us wall: many timers quickly
  RealTimeExecutor ex(clock);
  ex.set_lateness_capacity(8);
  int runs = 0;
  ex.schedule_every(kMs, [&] { ++runs; });
  ex.run(clock.now_us() + 100 * kMs);
  EXPECT_GE(runs, 100);
  EXPECT_EQ(ex.lateness_samples_us().size(), 8u) << "only the last 8 are kept";

  ex.set_lateness_capacity(0);
  ex.run(clock.now_us() + 20 * kMs);
  EXPECT_TRUE(ex.lateness_samples_us().empty()) << "capacity 0 records nothing";
}

TEST(RealTimeExecutor, DeliversBusMessagesInItsLoop) {
  const WallClock clock;
  LcmBus bus("memq://", &clock);
  RealTimeExecutor ex(clock, &bus);
  std::thread::id loop_thread;
  std::thread::id handler_thread;
  int64_t received_utime = 0;
  bus.subscribe<a3lcm::sim_clock_t>("A3_TEST_RT_CLOCK",
                                    [&](const a3lcm::sim_clock_t& msg, int64_t) {
                                      handler_thread = std::this_thread::get_id();
                                      received_utime = msg.utime_us;
                                      ex.stop();
                                    });
  ex.schedule_after(10 * kMs, [&] {
    loop_thread = std::this_thread::get_id();
    a3lcm::sim_clock_t msg{};
    msg.utime_us = 777;
    bus.publish("A3_TEST_RT_CLOCK", msg);
  });
  test::DeadlineThread runner([&] { ex.run(); });
  ASSERT_TRUE(runner.join_within(milliseconds(2000), [&] { ex.stop(); }))
      << "the message published on the bus was never delivered by the loop";
  EXPECT_EQ(received_utime, 777);
  EXPECT_EQ(handler_thread, loop_thread) << "bus callbacks run on the executor's thread";
}

}  // namespace
}  // namespace a3::common
