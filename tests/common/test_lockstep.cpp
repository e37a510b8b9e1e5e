// The lockstep pieces of the real-time runtime: the SteppedClock (time moves only by grants),
// the LockstepPacer (grants one quantum at a time, only once the vehicle answered and the wall
// clock allows; repeats an unanswered grant; counts the waits), the counter facility and the
// node statistics' JSON form. Real-time cases assert behaviour with generous bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <utility>
#include <vector>
#include <chrono>
#include <thread>

#include "a3lcm/sim_clock_t.hpp"
#include "common/channels.hpp"
#include "common/counters.hpp"
#include "common/lcm_bus.hpp"
#include "common/lockstep_pacer.hpp"
#include "common/node_stats.hpp"
#include "common/realtime_executor.hpp"

namespace a3::common {
namespace {

TEST(SteppedClock, MovesOnlyForwardAndOnlyByGrants) {
  SteppedClock clock(0);
  EXPECT_EQ(clock.now_us(), 0);
  EXPECT_TRUE(clock.due_mono_ns(0).has_value());
  EXPECT_FALSE(clock.due_mono_ns(1).has_value());  // not granted: no wall time can make it due
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(clock.now_us(), 0);
  EXPECT_TRUE(clock.advance_to(4000));
  EXPECT_FALSE(clock.advance_to(4000));  // a repeated grant
  EXPECT_FALSE(clock.advance_to(2000));  // an old one
  EXPECT_EQ(clock.now_us(), 4000);
  EXPECT_TRUE(clock.due_mono_ns(4000).has_value());
}

// A pacer on a real-time executor with an in-process bus; `answer` decides what the vehicle does
// with each grant it hears.
struct PacedRig {
  LcmBus bus{"memq://"};
  SteppedClock clock{0};
  RealTimeExecutor executor{clock, &bus};
  LockstepPacer pacer;
  std::atomic<int> grants_heard{0};
  std::thread thread;

  PacedRig(double rtf, const std::function<void(LockstepPacer&, int64_t)>& answer)
      : PacedRig(rtf, {}, [answer](LockstepPacer& p, const a3lcm::sim_clock_t& m) {
          if (answer) answer(p, m.utime_us);
        }) {}
  PacedRig(double rtf, std::vector<std::string> followers,
           const std::function<void(LockstepPacer&, const a3lcm::sim_clock_t&)>& answer)
      : pacer(clock, bus, config(rtf, std::move(followers))) {
    executor.set_clock_driver(&pacer);
    bus.subscribe<a3lcm::sim_clock_t>(channels::kClock, [this, answer](const a3lcm::sim_clock_t& m, int64_t) {
      ++grants_heard;
      answer(pacer, m);
    });
  }
  static LockstepConfig config(double rtf, std::vector<std::string> followers) {
    LockstepConfig c;
    c.quantum_us = 4000;
    c.real_time_factor = rtf;
    c.first_ack_us = 4000;
    c.followers = std::move(followers);
    return c;
  }
  void run_for(std::chrono::milliseconds wall) {
    thread = std::thread([this] { executor.run(); });
    std::this_thread::sleep_for(wall);
    executor.stop();
    thread.join();
  }
};

TEST(LockstepPacer, HoldsSimulatedTimeUntilTheVehicleAnswers) {
  PacedRig rig(1.0, nullptr);
  rig.run_for(std::chrono::milliseconds(150));
  // 0 and 4 ms need no answer; 8 ms needs the answer to 4 ms, which never came.
  EXPECT_EQ(rig.clock.now_us(), 4000);
  EXPECT_EQ(rig.pacer.stats().grants, 2u);
  // The unanswered grant went out again (every 20 ms), so one lost datagram cannot stall the loop.
  EXPECT_GE(rig.grants_heard.load(), 4);
}

TEST(LockstepPacer, AnsweredGrantsFollowTheWallClockAtTheFactor) {
  PacedRig rig(10.0, [](LockstepPacer& p, int64_t t) { p.note_ack(t); });
  rig.run_for(std::chrono::milliseconds(300));
  const LockstepStats s = rig.pacer.stats();
  EXPECT_GT(rig.clock.now_us(), 1'500'000);  // ~3 s of simulated time in 0.3 s of wall time
  EXPECT_LT(rig.clock.now_us(), 3'500'000);  // and never faster than the factor
  EXPECT_EQ(s.granted_us, rig.clock.now_us());
  EXPECT_LT(s.achieved_rtf, 10.5);
}

TEST(LockstepPacer, ALateVehicleSlowsSimulatedTimeAndTheWaitsAreCounted) {
  // The vehicle takes 6 ms of wall time for each 4 ms step at factor 1: simulated time must slow
  // down instead of running ahead of it.
  PacedRig rig(1.0, [](LockstepPacer& p, int64_t t) {
    std::this_thread::sleep_for(std::chrono::milliseconds(6));
    p.note_ack(t);
  });
  rig.run_for(std::chrono::milliseconds(400));
  const LockstepStats s = rig.pacer.stats();
  EXPECT_GT(s.waits, 10u);
  EXPECT_GT(s.wait_total_s, 0.01);
  EXPECT_LT(static_cast<double>(rig.clock.now_us()) * 1e-6, 0.4 * 0.85);
  EXPECT_LT(s.achieved_rtf, 0.85);
}

TEST(LockstepPacer, ASilentFollowerHoldsSimulatedTime) {
  // The vehicle answers; the follower "linkemu" never does: not even the first quantum passes.
  PacedRig rig(1.0, {"linkemu"}, [](LockstepPacer& p, const a3lcm::sim_clock_t& m) { p.note_ack(m.utime_us); });
  rig.run_for(std::chrono::milliseconds(100));
  EXPECT_EQ(rig.clock.now_us(), 0);
  EXPECT_EQ(rig.pacer.stats().grants, 1u);
}

TEST(LockstepPacer, GrantsATimeAgainWhileAFollowerHasSpokenAtIt) {
  // The follower publishes one message while it runs what was due at 8 ms: 8 ms is granted
  // again (round 1) and answered again in silence before 12 ms is granted.
  std::vector<std::pair<int64_t, int32_t>> heard;
  std::mutex heard_mutex;
  PacedRig rig(10.0, {"tool_server"}, [&](LockstepPacer& p, const a3lcm::sim_clock_t& m) {
    {
      std::lock_guard<std::mutex> lock(heard_mutex);
      heard.emplace_back(m.utime_us, m.round);
    }
    p.note_ack(m.utime_us);
    p.note_follower_ack("tool_server", m.utime_us, m.round, m.utime_us >= 8000 ? 1 : 0);
    p.note_follower_ack("someone_else", m.utime_us + 4000, 0, 5);  // not a follower: ignored
  });
  rig.run_for(std::chrono::milliseconds(100));
  EXPECT_GT(rig.clock.now_us(), 12000);
  EXPECT_EQ(rig.pacer.stats().rounds, 1u);
  std::lock_guard<std::mutex> lock(heard_mutex);
  const auto at = [&](int64_t t, int32_t round) { return std::find(heard.begin(), heard.end(), std::make_pair(t, round)); };
  ASSERT_NE(at(8000, 1), heard.end());
  ASSERT_NE(at(12000, 0), heard.end());
  EXPECT_LT(at(8000, 1), at(12000, 0));
  EXPECT_EQ(at(4000, 1), heard.end());  // nothing was said at 4 ms
}

TEST(CounterSet, NamesItsCountersOnce) {
  CounterSet set;
  Counter& steps = set.add("steps");
  Counter& bytes = set.add("up.bytes");
  ++steps;
  ++steps;
  bytes += 300;
  EXPECT_EQ(set.get("steps"), 2u);
  EXPECT_EQ(set.get("up.bytes"), 300u);
  EXPECT_THROW(set.add("steps"), std::logic_error);
  EXPECT_THROW(set.get("nothing"), std::out_of_range);
  ASSERT_EQ(set.snapshot().size(), 2u);
  EXPECT_EQ(set.snapshot()[0].first, "steps");
  EXPECT_EQ(to_text(set), "steps 2, up.bytes 300");
}

TEST(NodeStats, DottedCounterNamesNestAndTimingsTravel) {
  CounterSet set;
  set.add("up.dropped.queue_full") += 3;
  set.add("up.delivered") += 7;
  set.add("records") += 1;
  const a3lcm::node_stats_t m = make_node_stats("linkemu", 42, true, set, {{"lateness_p99_us", 12.5}});
  EXPECT_EQ(m.node, "linkemu");
  EXPECT_TRUE(m.is_final);
  const nlohmann::json j = node_stats_json(m);
  EXPECT_EQ(j["counters"]["up"]["dropped"]["queue_full"], 3);
  EXPECT_EQ(j["counters"]["up"]["delivered"], 7);
  EXPECT_EQ(j["counters"]["records"], 1);
  EXPECT_DOUBLE_EQ(j["timing"]["lateness_p99_us"].get<double>(), 12.5);
  // Through LCM's encoding and back.
  std::vector<uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
  ASSERT_EQ(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  a3lcm::node_stats_t back;
  ASSERT_GT(back.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
  EXPECT_EQ(node_stats_json(back), j);
}

}  // namespace
}  // namespace a3::common
