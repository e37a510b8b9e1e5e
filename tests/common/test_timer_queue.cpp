// TimerQueue, the deterministic core of both executors: (time, insertion) order, periodic
// re-arming on schedule, cancellation (also of a timer whose callback is running), ids that
// stay unique when a freed slot is reused, and the order against a sorted reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/timer_queue.hpp"

namespace a3::common {
namespace {

// Pops and runs everything due at or before t_us, as an executor does; records the times.
void drain(TimerQueue& queue, int64_t t_us, std::vector<std::string>& times) {
  while (auto due = queue.pop_due(t_us)) {
    times.push_back(std::to_string(due->time_us));
    due->fn();
    queue.finish(*due);
  }
}

// A reference model of pending timers for the randomized tests: the one that must run next is
// the earliest (time, insertion order) of those pending.
struct RefTimer {
  int64_t time_us;
  uint64_t order;
  TimerId id;
  int64_t period_us;
  bool pending;
};

int earliest_pending(const std::vector<RefTimer>& refs) {
  int earliest = -1;
  for (int i = 0; i < static_cast<int>(refs.size()); ++i) {
    if (!refs[i].pending) continue;
    if (earliest < 0 || refs[i].time_us < refs[earliest].time_us ||
        (refs[i].time_us == refs[earliest].time_us && refs[i].order < refs[earliest].order)) {
      earliest = i;
    }
  }
  return earliest;
}

TEST(TimerQueue, OrdersByTimeThenInsertion) {
  TimerQueue queue;
  std::vector<std::string> ran;
  queue.add(300, 0, [&] { ran.push_back("c300"); });
  queue.add(100, 0, [&] { ran.push_back("a100"); });
  queue.add(200, 0, [&] { ran.push_back("b200-first"); });
  queue.add(200, 0, [&] { ran.push_back("b200-second"); });
  queue.add(200, 0, [&] { ran.push_back("b200-third"); });
  EXPECT_EQ(queue.next_time_us(), 100);
  std::vector<std::string> times;
  drain(queue, 1000, times);
  EXPECT_EQ(ran, (std::vector<std::string>{"a100", "b200-first", "b200-second", "b200-third",
                                           "c300"}));
  EXPECT_EQ(times, (std::vector<std::string>{"100", "200", "200", "200", "300"}));
  EXPECT_EQ(queue.size(), 0u);
  EXPECT_FALSE(queue.next_time_us().has_value());
}

TEST(TimerQueue, PopsOnlyWhatIsDue) {
  TimerQueue queue;
  queue.add(100, 0, [] {});
  queue.add(101, 0, [] {});
  EXPECT_FALSE(queue.pop_due(99).has_value());
  auto due = queue.pop_due(100);
  ASSERT_TRUE(due.has_value());
  EXPECT_EQ(due->time_us, 100);
  queue.finish(*due);
  EXPECT_FALSE(queue.pop_due(100).has_value()) << "the timer at 101 is not due at 100";
  EXPECT_EQ(queue.next_time_us(), 101);
}

TEST(TimerQueue, PeriodicTimerKeepsItsScheduleAndIsRearmedBeforeItRuns) {
  TimerQueue queue;
  int runs = 0;
  const TimerId id = queue.add(1000, 250, [&] { ++runs; });
  std::vector<int64_t> times;
  // Pop late (at 1900): every missed period is still owed, at its own scheduled time.
  while (auto due = queue.pop_due(1900)) {
    EXPECT_EQ(due->id, id);
    times.push_back(due->time_us);
    // Re-armed already: the next period is pending while this callback would run.
    EXPECT_EQ(queue.next_time_us(), due->time_us + 250);
    due->fn();
    queue.finish(*due);
  }
  EXPECT_EQ(times, (std::vector<int64_t>{1000, 1250, 1500, 1750}));
  EXPECT_EQ(runs, 4);
  EXPECT_EQ(queue.size(), 1u) << "a periodic timer stays until cancelled";
  EXPECT_EQ(queue.next_time_us(), 2000);
}

TEST(TimerQueue, PeriodicTimerInterleavesWithOneShotsInOrder) {
  TimerQueue queue;
  std::vector<std::string> ran;
  queue.add(0, 100, [&] { ran.push_back("p"); });
  queue.add(100, 0, [&] { ran.push_back("x100"); });  // inserted before p's re-arm at 100
  queue.add(250, 0, [&] { ran.push_back("x250"); });
  std::vector<std::string> times;
  drain(queue, 300, times);
  EXPECT_EQ(ran, (std::vector<std::string>{"p", "x100", "p", "p", "x250", "p"}));
  EXPECT_EQ(times, (std::vector<std::string>{"0", "100", "100", "200", "250", "300"}));
}

TEST(TimerQueue, CancelRemovesAPendingTimerAndIgnoresUnknownIds) {
  TimerQueue queue;
  bool a = false, b = false;
  const TimerId ida = queue.add(10, 0, [&] { a = true; });
  queue.add(20, 0, [&] { b = true; });
  queue.cancel(ida);
  queue.cancel(ida);     // twice: ignored
  queue.cancel(12345);   // unknown: ignored
  EXPECT_EQ(queue.size(), 1u);
  EXPECT_EQ(queue.next_time_us(), 20);
  std::vector<std::string> times;
  drain(queue, 100, times);
  EXPECT_FALSE(a);
  EXPECT_TRUE(b);
}

TEST(TimerQueue, PeriodicCallbackMayCancelItsOwnTimer) {
  TimerQueue queue;
  int runs = 0;
  TimerId id = 0;
  id = queue.add(0, 10, [&] {
    if (++runs == 3) queue.cancel(id);
  });
  std::vector<std::string> times;
  drain(queue, 1000, times);
  EXPECT_EQ(runs, 3);
  EXPECT_EQ(queue.size(), 0u);
  EXPECT_FALSE(queue.next_time_us().has_value());
}

TEST(TimerQueue, OneShotCallbackMayCancelItselfAndAddTimers) {
  TimerQueue queue;
  std::vector<std::string> ran;
  TimerId id = 0;
  id = queue.add(5, 0, [&] {
    ran.push_back("first");
    queue.cancel(id);  // cancelling a running one-shot is harmless
    queue.add(5, 0, [&] { ran.push_back("added-same-time"); });
    queue.add(7, 0, [&] { ran.push_back("added-later"); });
  });
  std::vector<std::string> times;
  drain(queue, 10, times);
  EXPECT_EQ(ran, (std::vector<std::string>{"first", "added-same-time", "added-later"}));
  EXPECT_EQ(queue.size(), 0u);
}

TEST(TimerQueue, IdsAreUniqueAndIncreasing) {
  TimerQueue queue;
  TimerId last = 0;
  for (int i = 0; i < 100; ++i) {
    const TimerId id = queue.add(i % 7, i % 3, [] {});
    EXPECT_GT(id, last);
    last = id;
  }
  EXPECT_EQ(queue.size(), 100u);
}

TEST(TimerQueue, AnOldIdCancelsNothingAfterItsSlotIsReused) {
  TimerQueue queue;
  const TimerId old_id = queue.add(10, 0, [] {});
  queue.cancel(old_id);
  bool ran = false;
  const TimerId new_id = queue.add(20, 0, [&] { ran = true; });  // takes the freed slot
  EXPECT_NE(new_id, old_id);
  queue.cancel(old_id);
  EXPECT_EQ(queue.size(), 1u);
  std::vector<std::string> times;
  drain(queue, 100, times);
  EXPECT_TRUE(ran);
  EXPECT_EQ(times, (std::vector<std::string>{"20"}));
}

TEST(TimerQueue, PeriodicCallbackMayCancelItselfAndStartAReplacementInItsSlot) {
  TimerQueue queue;
  std::vector<std::string> ran;
  TimerId id = 0;
  id = queue.add(0, 10, [&] {
    ran.push_back("old");
    queue.cancel(id);
    queue.add(25, 10, [&] { ran.push_back("new"); });
  });
  std::vector<std::string> times;
  drain(queue, 45, times);
  EXPECT_EQ(ran, (std::vector<std::string>{"old", "new", "new", "new"}));
  EXPECT_EQ(times, (std::vector<std::string>{"0", "25", "35", "45"}));
  EXPECT_EQ(queue.size(), 1u) << "finishing the old timer leaves the new one alone";
}

TEST(TimerQueue, APeriodicTimerWhoseCallbackThrowsKeepsItsCallback) {
  TimerQueue queue;
  int runs = 0;
  queue.add(0, 10, [&] {
    if (++runs == 1) throw std::runtime_error("first run fails");
  });
  auto due = queue.pop_due(0);
  ASSERT_TRUE(due.has_value());
  EXPECT_THROW(due->fn(), std::runtime_error);
  queue.finish(*due);  // as an executor does before passing the exception on
  std::vector<std::string> times;
  drain(queue, 20, times);
  EXPECT_EQ(runs, 3);
  EXPECT_EQ(times, (std::vector<std::string>{"10", "20"}));
}

// Many timers at few distinct times, two thirds of them cancelled (enough for the heap to drop
// its cancelled entries in bulk): the run order is (time, insertion), as a stable sort gives.
TEST(TimerQueue, OrderMatchesAStableSortWithManyTiesAndCancels) {
  TimerQueue queue;
  std::mt19937 rng(16);
  std::uniform_int_distribution<int64_t> time_us(0, 20);
  struct Added {
    int64_t time_us;
    int label;
    TimerId id;
  };
  std::vector<Added> added;
  std::vector<int> ran;
  for (int label = 0; label < 3000; ++label) {
    const int64_t t = time_us(rng);
    added.push_back({t, label, queue.add(t, 0, [&ran, label] { ran.push_back(label); })});
  }
  std::vector<int> expected;
  std::stable_sort(added.begin(), added.end(),
                   [](const Added& a, const Added& b) { return a.time_us < b.time_us; });
  for (const Added& a : added) {
    if (a.label % 3 != 0) {
      queue.cancel(a.id);
    } else {
      expected.push_back(a.label);
    }
  }
  EXPECT_EQ(queue.size(), expected.size());
  std::vector<std::string> times;
  drain(queue, 100, times);
  EXPECT_EQ(ran, expected);
  EXPECT_EQ(queue.size(), 0u);
}

// Callbacks add timers for their own time (these take the queue's FIFO) and for later, and
// cancel pending ones; each timer that runs must be the earliest (time, insertion) of those
// pending, as a reference list kept beside the queue says.
TEST(TimerQueue, TimersAddedForTheCurrentTimeKeepTheOrder) {
  TimerQueue queue;
  std::mt19937 rng(42);
  std::vector<RefTimer> refs;  // index = label
  int runs = 0, wrong = 0, cancels = 0, now_adds = 0;
  std::function<void(int64_t)> add;
  auto run = [&](int label) {
    ++runs;
    wrong += label == earliest_pending(refs) ? 0 : 1;
    refs[label].pending = false;
    const int64_t now = refs[label].time_us;
    if (refs.size() < 4000) {
      const int n = 1 + static_cast<int>(rng() % 2);
      for (int k = 0; k < n; ++k) {
        const bool at_now = rng() % 2 == 0;
        now_adds += at_now ? 1 : 0;
        add(at_now ? now : now + static_cast<int64_t>(rng() % 4));
      }
    }
    if (rng() % 4 == 0) {
      const std::size_t victim = rng() % refs.size();
      if (refs[victim].pending) {
        queue.cancel(refs[victim].id);
        refs[victim].pending = false;
        ++cancels;
      }
    }
  };
  add = [&](int64_t t) {
    const int label = static_cast<int>(refs.size());
    refs.push_back({t, refs.size(), 0, 0, true});
    refs[label].id = queue.add(t, 0, [&run, label] { run(label); });
  };
  for (int i = 0; i < 50; ++i) add(static_cast<int64_t>(rng() % 10));
  std::vector<std::string> times;
  drain(queue, 1'000'000, times);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(queue.size(), 0u);
  EXPECT_GT(runs, 1000);
  EXPECT_GT(now_adds, 300);
  EXPECT_GT(cancels, 50);
  EXPECT_TRUE(std::none_of(refs.begin(), refs.end(), [](const RefTimer& r) { return r.pending; }));
}

// Periodic timers (re-armed in the heap, or in the head slot when they are the earliest)
// among one-shots added by callbacks for now, for just after now (the head slot) and for
// later, with cancels: every timer that runs is the earliest (time, insertion) pending in a
// reference model beside the queue, and a periodic one runs every period until cancelled.
TEST(TimerQueue, PeriodicAndOneShotTimersInterleaveAsAReferenceSaysWhereverTheyWait) {
  TimerQueue queue;
  std::mt19937 rng(7);
  std::vector<RefTimer> refs;  // index = label
  uint64_t next_order = 0;
  int runs = 0, wrong = 0, periodic_runs = 0;
  std::function<void(int64_t, int64_t)> add;
  auto run = [&](int label) {
    ++runs;
    wrong += label == earliest_pending(refs) ? 0 : 1;
    RefTimer& ref = refs[label];
    const int64_t now = ref.time_us;
    if (ref.period_us > 0) {
      ++periodic_runs;
      ref.time_us += ref.period_us;  // re-armed before its callback runs: a new insertion
      ref.order = next_order++;
    } else {
      ref.pending = false;
    }
    if (refs.size() < 3000) {
      const unsigned kind = rng() % 3;
      add(kind == 0 ? now : now + 1 + static_cast<int64_t>(rng() % (kind == 1 ? 2 : 20)), 0);
    }
    if (rng() % 5 == 0) {
      const std::size_t victim = rng() % refs.size();
      if (refs[victim].pending) {
        queue.cancel(refs[victim].id);
        refs[victim].pending = false;
      }
    }
  };
  add = [&](int64_t t, int64_t period_us) {
    const int label = static_cast<int>(refs.size());
    refs.push_back({t, next_order++, 0, period_us, true});
    refs[label].id = queue.add(t, period_us, [&run, label] { run(label); });
  };
  for (int i = 0; i < 6; ++i) add(static_cast<int64_t>(rng() % 10), 3 + i);
  for (int i = 0; i < 20; ++i) add(static_cast<int64_t>(rng() % 10), 0);
  std::vector<std::string> times;
  drain(queue, 20'000, times);
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(runs, 3000);
  EXPECT_GT(periodic_runs, 1000);
}

TEST(TimerQueue, ATimerForTheCurrentTimeRunsAfterThoseAlreadyDueThenAndCanBeCancelled) {
  TimerQueue queue;
  std::vector<std::string> order;
  TimerId doomed = 0;
  queue.add(10, 0, [&] {
    order.push_back("a");
    queue.add(10, 0, [&] { order.push_back("c"); });
    doomed = queue.add(10, 0, [&] { order.push_back("never"); });
    queue.add(10, 0, [&] {
      order.push_back("d");
      queue.add(10, 0, [&] { order.push_back("e"); });
    });
    queue.cancel(doomed);
  });
  queue.add(10, 0, [&] { order.push_back("b"); });
  queue.add(11, 0, [&] { order.push_back("f"); });
  EXPECT_EQ(queue.next_time_us(), 10);
  std::vector<std::string> times;
  drain(queue, 10, times);
  EXPECT_EQ(order, (std::vector<std::string>{"a", "b", "c", "d", "e"}));
  EXPECT_EQ(queue.next_time_us(), 11);
  drain(queue, 11, times);
  EXPECT_EQ(order.back(), "f");
  EXPECT_EQ(queue.size(), 0u);
}

}  // namespace
}  // namespace a3::common
