// VirtualScheduler: (time, insertion) order, periodic timers without drift, cancellation,
// run_until and the clock, request_stop, events in the past, determinism.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/rng.hpp"
#include "common/virtual_scheduler.hpp"

namespace a3::common {
namespace {

using Trace = std::vector<std::pair<int64_t, std::string>>;

TEST(VirtualScheduler, RunsEventsInTimeThenInsertionOrderWithTheClockAtEachEvent) {
  VirtualScheduler s;
  Trace trace;
  auto note = [&](std::string name) {
    return [&trace, &s, name] { trace.emplace_back(s.clock().now_us(), name); };
  };
  s.schedule_at(300, note("c"));
  s.schedule_at(100, note("a"));
  s.schedule_at(200, note("b1"));
  s.schedule_at(200, note("b2"));
  s.schedule_at(200, note("b3"));
  EXPECT_EQ(s.pending(), 5u);
  EXPECT_EQ(s.run_until(1000), 5u);
  EXPECT_EQ(trace, (Trace{{100, "a"}, {200, "b1"}, {200, "b2"}, {200, "b3"}, {300, "c"}}));
  EXPECT_EQ(s.events_run(), 5u);
  EXPECT_EQ(s.pending(), 0u);
}

TEST(VirtualScheduler, EventScheduledForTheCurrentTimeRunsAfterThoseAlreadyDue) {
  VirtualScheduler s;
  std::vector<std::string> ran;
  s.schedule_at(50, [&] {
    ran.push_back("first");
    s.schedule_at(50, [&] { ran.push_back("added-by-first"); });
  });
  s.schedule_at(50, [&] { ran.push_back("second"); });
  s.run_until(50);
  EXPECT_EQ(ran, (std::vector<std::string>{"first", "second", "added-by-first"}));
}

TEST(VirtualScheduler, PeriodicTimerKeepsItsScheduleWithoutDrift) {
  VirtualScheduler s(7);  // start at 7 us so the schedule is not a multiple of anything round
  std::vector<int64_t> times;
  s.schedule_every(333, [&] { times.push_back(s.clock().now_us()); });
  // Run in uneven chunks: the schedule must not depend on where run_until stops.
  for (int64_t end : {100, 1000, 1001, 4000, 9999, 10'007}) s.run_until(end);
  ASSERT_EQ(times.size(), 30u);
  for (std::size_t k = 0; k < times.size(); ++k) {
    EXPECT_EQ(times[k], 7 + 333 * static_cast<int64_t>(k + 1)) << "period " << k;
  }
}

TEST(VirtualScheduler, PeriodicTimerWithExplicitFirstTime) {
  VirtualScheduler s;
  std::vector<int64_t> times;
  s.schedule(50, 100, [&] { times.push_back(s.clock().now_us()); });
  s.run_until(450);
  EXPECT_EQ(times, (std::vector<int64_t>{50, 150, 250, 350, 450}));
}

TEST(VirtualScheduler, NegativePeriodIsRejected) {
  VirtualScheduler s;
  EXPECT_THROW(s.schedule(0, -1, [] {}), std::invalid_argument);
  EXPECT_EQ(s.pending(), 0u);
}

TEST(VirtualScheduler, CancelledTimerNeverRuns) {
  VirtualScheduler s;
  int a = 0, b = 0;
  const TimerId ta = s.schedule_at(100, [&] { ++a; });
  s.schedule_at(100, [&] { ++b; });
  s.cancel(ta);
  s.cancel(999);  // unknown id: ignored
  s.run_until(200);
  EXPECT_EQ(a, 0);
  EXPECT_EQ(b, 1);
}

TEST(VirtualScheduler, CallbackCancelsAnotherTimerDueAtTheSameTime) {
  VirtualScheduler s;
  bool victim_ran = false;
  TimerId victim = 0;
  s.schedule_at(100, [&] { s.cancel(victim); });
  victim = s.schedule_at(100, [&] { victim_ran = true; });
  EXPECT_EQ(s.run_until(200), 1u);
  EXPECT_FALSE(victim_ran);
}

TEST(VirtualScheduler, PeriodicCallbackCancelsItsOwnTimer) {
  VirtualScheduler s;
  int runs = 0;
  TimerId id = 0;
  id = s.schedule_every(10, [&] {
    if (++runs == 4) s.cancel(id);
  });
  s.run_until(1000);
  EXPECT_EQ(runs, 4);
  EXPECT_EQ(s.pending(), 0u);
}

// The rig catches a node's exception and ends the episode; a test may catch it and go on:
// the periodic timer that threw is still armed, with its callback.
TEST(VirtualScheduler, APeriodicTimerThatThrewRunsAgainAfterTheExceptionIsCaught) {
  VirtualScheduler s;
  std::vector<int64_t> times;
  s.schedule_every(10, [&] {
    times.push_back(s.clock().now_us());
    if (times.size() == 2) throw std::runtime_error("second run fails");
  });
  EXPECT_THROW(s.run_until(100), std::runtime_error);
  EXPECT_EQ(s.clock().now_us(), 20);
  EXPECT_EQ(s.pending(), 1u);
  s.run_until(40);
  EXPECT_EQ(times, (std::vector<int64_t>{10, 20, 30, 40}));
}

TEST(VirtualScheduler, RunUntilSetsTheClockAndRunsEventsAtTheEndButNotAfter) {
  VirtualScheduler s;
  EXPECT_EQ(s.run_until(1234), 0u);
  EXPECT_EQ(s.clock().now_us(), 1234) << "time passes even with nothing to do";
  bool at_end = false, after_end = false;
  s.schedule_at(2000, [&] { at_end = true; });
  s.schedule_at(2001, [&] { after_end = true; });
  EXPECT_EQ(s.run_until(2000), 1u);
  EXPECT_TRUE(at_end);
  EXPECT_FALSE(after_end);
  EXPECT_EQ(s.clock().now_us(), 2000);
  EXPECT_EQ(s.pending(), 1u);
  // Asking for an earlier end does not move the clock back.
  EXPECT_EQ(s.run_until(1500), 0u);
  EXPECT_EQ(s.clock().now_us(), 2000);
  EXPECT_FALSE(after_end);
}

TEST(VirtualScheduler, RequestStopEndsRunUntilAtTheEventAndResumesLater) {
  VirtualScheduler s;
  std::vector<int64_t> times;
  s.schedule_every(100, [&] {
    times.push_back(s.clock().now_us());
    if (s.clock().now_us() == 300) s.request_stop();
  });
  EXPECT_EQ(s.run_until(1000), 3u);
  EXPECT_TRUE(s.stop_requested());
  EXPECT_EQ(s.clock().now_us(), 300) << "the clock stays at the stopping event";
  EXPECT_EQ(times, (std::vector<int64_t>{100, 200, 300}));
  // The next run starts afresh and continues the schedule.
  EXPECT_EQ(s.run_until(550), 2u);
  EXPECT_FALSE(s.stop_requested());
  EXPECT_EQ(times, (std::vector<int64_t>{100, 200, 300, 400, 500}));
  EXPECT_EQ(s.clock().now_us(), 550);
}

TEST(VirtualScheduler, EventInThePastRunsNowAndTheClockNeverGoesBack) {
  VirtualScheduler s;
  s.run_until(1000);
  int64_t ran_at = -1;
  s.schedule_at(200, [&] { ran_at = s.clock().now_us(); });
  s.schedule(-50, 0, [] {});
  s.run_until(1000);
  EXPECT_EQ(ran_at, 1000);
  // Inside a callback too: a past time means after what is already due now.
  std::vector<std::string> ran;
  s.schedule_at(1500, [&] {
    s.schedule_at(10, [&] { ran.push_back("past@" + std::to_string(s.clock().now_us())); });
    ran.push_back("first");
  });
  s.schedule_at(1500, [&] { ran.push_back("second"); });
  s.run_until(2000);
  EXPECT_EQ(ran, (std::vector<std::string>{"first", "second", "past@1500"}));
  EXPECT_EQ(s.clock().now_us(), 2000);
}

TEST(VirtualScheduler, PeriodicTimerStartingInThePastKeepsItsPeriodFromNow) {
  VirtualScheduler s(1000);
  std::vector<int64_t> times;
  s.schedule(10, 100, [&] { times.push_back(s.clock().now_us()); });
  s.run_until(1300);
  EXPECT_EQ(times, (std::vector<int64_t>{1000, 1100, 1200, 1300}));
}

TEST(VirtualScheduler, ScheduleAfterAndEveryAreRelativeToNow) {
  VirtualScheduler s;
  s.run_until(5000);
  int64_t after = -1;
  std::vector<int64_t> every;
  s.schedule_after(250, [&] { after = s.clock().now_us(); });
  const TimerId id = s.schedule_every(1000, [&] { every.push_back(s.clock().now_us()); });
  s.run_until(7500);
  s.cancel(id);
  s.run_until(20000);
  EXPECT_EQ(after, 5250);
  EXPECT_EQ(every, (std::vector<int64_t>{6000, 7000}));
}

TEST(VirtualScheduler, StepRunsOneEventAtATime) {
  VirtualScheduler s;
  std::vector<int64_t> times;
  s.schedule_at(30, [&] { times.push_back(s.clock().now_us()); });
  s.schedule_at(10, [&] { times.push_back(s.clock().now_us()); });
  EXPECT_TRUE(s.step());
  EXPECT_EQ(s.clock().now_us(), 10);
  EXPECT_EQ(times, (std::vector<int64_t>{10}));
  EXPECT_TRUE(s.step());
  EXPECT_EQ(s.clock().now_us(), 30);
  EXPECT_FALSE(s.step());
  EXPECT_EQ(s.clock().now_us(), 30);
  EXPECT_EQ(s.events_run(), 2u);
}

// A busy, seeded workload: timers with ties, callbacks that schedule and cancel others.
// Trace entries: (time, timer index), follow-up events as index + 100.
std::vector<std::pair<int64_t, int>> run_workload(uint64_t seed) {
  VirtualScheduler s;
  std::vector<std::pair<int64_t, int>> trace;
  Rng rng = RngStreams(seed).stream("scheduler-test");
  std::vector<TimerId> ids;
  for (int i = 0; i < 20; ++i) {
    const int64_t first = static_cast<int64_t>(rng.uniform(0, 50)) * 10;  // many ties
    const int64_t period = i % 3 == 0 ? 0 : static_cast<int64_t>(rng.uniform(1, 20)) * 10;
    ids.push_back(s.schedule(first, period, [&, i] {
      trace.emplace_back(s.clock().now_us(), i);
      const double u = rng.uniform01();
      if (u < 0.2) {
        s.schedule_after(static_cast<int64_t>(rng.uniform(0, 5)) * 10,
                         [&, i] { trace.emplace_back(s.clock().now_us(), i + 100); });
      } else if (u < 0.25) {
        s.cancel(ids[static_cast<std::size_t>(rng.uniform(0, static_cast<double>(ids.size())))]);
      }
    }));
  }
  s.run_until(2000);
  return trace;
}

TEST(VirtualScheduler, IdenticalRunsGiveIdenticalTraces) {
  const auto first = run_workload(42);
  const auto second = run_workload(42);
  ASSERT_GT(first.size(), 100u) << "the workload should be busy";
  EXPECT_EQ(first, second);
  for (std::size_t i = 1; i < first.size(); ++i) {
    ASSERT_LE(first[i - 1].first, first[i].first) << "time went back at event " << i;
  }
  EXPECT_NE(run_workload(43), first) << "a different seed gives a different workload";
}

}  // namespace
}  // namespace a3::common
