// The virtual-time event path allocates nothing per event once warmed up: scheduling and
// running one-shot and periodic timers (small callbacks), cancelling timers, timers that
// replace themselves, publishing raw bytes on the VirtualBus and delivering them, and typed
// publish and typed (decoding) delivery.
// Counted by replacing operator new in this test program; each test warms up with the same
// workload first (vectors reach capacity). The virtual CAN bus has its own in tests/bridge.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "a3lcm/vehicle_state_t.hpp"
#include "common/timer_queue.hpp"
#include "common/virtual_bus.hpp"
#include "common/virtual_scheduler.hpp"
#include "tests/common/bus_test_messages.hpp"
#include "tests/common/counting_operator_new.hpp"

namespace a3::common {
namespace {

using test::allocations_counted;
using test::start_counting_allocations;

// One round: 2000 one-shot events at spread times, each scheduling a follow-up, run to the end.
void one_shot_round(VirtualScheduler& scheduler, int& runs) {
  const int64_t t0 = scheduler.clock().now_us();
  for (int i = 0; i < 2000; ++i) {
    scheduler.schedule_at(t0 + (i * 37) % 1000, [&scheduler, &runs] {
      ++runs;
      scheduler.schedule_after(5, [&runs] { ++runs; });
    });
  }
  scheduler.run_until(t0 + 2000);
}

TEST(EventAllocations, OneShotEventsAllocateNothingAfterWarmUp) {
  VirtualScheduler scheduler;
  int runs = 0;
  one_shot_round(scheduler, runs);
  start_counting_allocations();
  one_shot_round(scheduler, runs);
  EXPECT_EQ(allocations_counted(), 0);
  EXPECT_EQ(runs, 2 * 4000);
}

TEST(EventAllocations, PeriodicTimersAndCancelsAllocateNothingAfterWarmUp) {
  VirtualScheduler scheduler;
  int ticks = 0;
  for (int i = 1; i <= 8; ++i) scheduler.schedule_every(100 * i, [&ticks] { ++ticks; });
  auto round = [&] {
    // A timeout re-armed every step and cancelled before it fires, as watchdogs do.
    TimerId timeout = 0;
    for (int step = 0; step < 1000; ++step) {
      scheduler.cancel(timeout);
      timeout = scheduler.schedule_after(50'000, [&ticks] { ticks = -1000000; });
      scheduler.run_until(scheduler.clock().now_us() + 100);
    }
    scheduler.cancel(timeout);
  };
  round();
  start_counting_allocations();
  round();
  EXPECT_EQ(allocations_counted(), 0);
  EXPECT_GT(ticks, 2000);
}

// A node's pattern: a state arrives, a command goes out from inside the handler. The channel
// names are longer than std::string's inline buffer, so reusing a message's name matters.
TEST(EventAllocations, VirtualBusPublishAndDeliveryAllocateNothingAfterWarmUp) {
  VirtualScheduler scheduler;
  VirtualBus bus(scheduler);
  const std::string state = "A3_VEHICLE_STATE_FOR_TESTS", command = "A3_COMMAND_FOR_TESTS";
  const std::vector<uint8_t> payload(120, 0xA5), reply(24, 0x5A);
  std::size_t state_bytes = 0, command_bytes = 0;
  for (int s = 0; s < 3; ++s) {
    bus.subscribe_raw(state, [&](const std::string&, const uint8_t*, std::size_t size, int64_t) {
      state_bytes += size;
      bus.publish_raw(command, reply.data(), reply.size());
    });
  }
  bus.subscribe_raw(command, [&command_bytes](const std::string&, const uint8_t*, std::size_t size,
                                              int64_t) { command_bytes += size; });
  auto round = [&] {
    for (int i = 0; i < 1000; ++i) {
      bus.publish_raw(state, payload.data(), payload.size());
      if (i % 3 == 0) scheduler.run_until(scheduler.clock().now_us() + 10);
    }
    scheduler.run_until(scheduler.clock().now_us() + 10);
  };
  round();
  start_counting_allocations();
  round();
  EXPECT_EQ(allocations_counted(), 0);
  EXPECT_EQ(state_bytes, 2u * 1000u * 3u * payload.size());
  EXPECT_EQ(command_bytes, 2u * 1000u * 3u * reply.size());
}

// The same pattern through the typed helpers: publish encodes into a reused buffer, also from
// inside a handler, and several typed subscribers decode (once) without allocating.
TEST(EventAllocations, TypedPublishAndDeliveryAllocateNothingAfterWarmUp) {
  VirtualScheduler scheduler;
  VirtualBus bus(scheduler);
  const std::string state = "A3_VEHICLE_STATE_FOR_TESTS", echo = "A3_STATE_ECHO_FOR_TESTS";
  int64_t state_sum = 0, echo_sum = 0;
  for (int s = 0; s < 3; ++s) {
    bus.subscribe<a3lcm::vehicle_state_t>(state, [&](const a3lcm::vehicle_state_t& m, int64_t) {
      state_sum += m.utime_us;
      a3lcm::vehicle_state_t reply = m;
      reply.utime_us = m.utime_us + 1;
      bus.publish(echo, reply);
    });
  }
  bus.subscribe<a3lcm::vehicle_state_t>(echo, [&echo_sum](const a3lcm::vehicle_state_t& m, int64_t) {
    echo_sum += m.utime_us;
  });
  int64_t t = 0;
  auto round = [&] {
    for (int i = 0; i < 1000; ++i) {
      bus.publish(state, test::make_state(++t));
      if (i % 3 == 0) scheduler.run_until(scheduler.clock().now_us() + 10);
    }
    scheduler.run_until(scheduler.clock().now_us() + 10);
  };
  round();
  start_counting_allocations();
  round();
  EXPECT_EQ(allocations_counted(), 0);
  const int64_t sum_of_times = t * (t + 1) / 2;  // every utime 1..t, each to 3 subscribers
  EXPECT_EQ(state_sum, 3 * sum_of_times);
  EXPECT_EQ(echo_sum, 3 * (sum_of_times + t));
}

// A periodic timer that, now and then, cancels itself and starts its replacement from inside
// its own callback (a node changing its rate).
TEST(EventAllocations, TimersReplacingThemselvesAllocateNothingAfterWarmUp) {
  VirtualScheduler scheduler;
  int runs = 0;
  TimerId periodic = 0;
  struct Replacer {
    VirtualScheduler* scheduler;
    TimerId* id;
    void operator()() const {
      if (scheduler->clock().now_us() % 700 == 0) {
        scheduler->cancel(*id);
        *id = scheduler->schedule_every(100, *this);
      }
    }
  };
  periodic = scheduler.schedule_every(100, Replacer{&scheduler, &periodic});
  scheduler.schedule_every(50, [&runs] { ++runs; });
  scheduler.run_until(100'000);
  start_counting_allocations();
  scheduler.run_until(200'000);
  EXPECT_EQ(allocations_counted(), 0);
  EXPECT_EQ(runs, 4000);
  EXPECT_EQ(scheduler.pending(), 2u);
}

TEST(EventAllocations, TheCounterSeesAnAllocation) {
  start_counting_allocations();
  std::vector<int>* volatile p = new std::vector<int>(1000);  // volatile: not elided
  const long counted = allocations_counted();
  delete p;
  EXPECT_GE(counted, 2);
}

}  // namespace
}  // namespace a3::common
