// Runtimes with small test nodes: two nodes exchanging LCM messages with timers under the
// VirtualRuntime (exact virtual timing, deterministic for a seed), and a node on its own
// thread under RealTimeNodeThread (start, stop, a failing node reported).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "a3lcm/link_message_t.hpp"
#include "common/rng.hpp"
#include "common/runtime.hpp"
#include "tests/common/common_test_util.hpp"

namespace a3::common {
namespace {

constexpr const char* kPing = "A3_TEST_PING";
constexpr const char* kPong = "A3_TEST_PONG";

struct Event {
  int64_t t_us;
  std::string what;
  int64_t id;
  bool operator==(const Event&) const = default;
};

// Sends a ping every period; records each pong with its round-trip time.
class PingNode final : public Node {
 public:
  explicit PingNode(int64_t period_us) : period_us_(period_us) {}
  std::string name() const override { return "ping"; }
  void start(Executor& executor, Bus& bus) override {
    bus.subscribe<a3lcm::link_message_t>(
        kPong, [this, &executor](const a3lcm::link_message_t& m, int64_t recv_utime_us) {
          EXPECT_EQ(recv_utime_us, executor.clock().now_us());
          std::lock_guard<std::mutex> lock(mutex_);
          events_.push_back({recv_utime_us, "pong rtt=" + std::to_string(recv_utime_us - m.sent_utime_us),
                             m.message_id});
        });
    executor.schedule_every(period_us_, [this, &executor, &bus] {
      a3lcm::link_message_t m{};
      m.message_id = ++sent_;
      m.utime_us = m.sent_utime_us = executor.clock().now_us();
      m.sender = "ping";
      m.kind = "ping";
      const std::string text = "ping " + std::to_string(m.message_id);
      m.payload.assign(text.begin(), text.end());
      m.payload_length = static_cast<int32_t>(m.payload.size());
      bus.publish(kPing, m);
      std::lock_guard<std::mutex> lock(mutex_);
      events_.push_back({m.utime_us, "ping", m.message_id});
    });
  }
  std::vector<Event> events() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return events_;
  }

 private:
  int64_t period_us_;
  int64_t sent_ = 0;
  mutable std::mutex mutex_;
  std::vector<Event> events_;
};

// Answers each ping after a delay drawn from a seeded stream (fixed when min == max).
class PongNode final : public Node {
 public:
  PongNode(uint64_t seed, int64_t min_delay_us, int64_t max_delay_us)
      : rng_(RngStreams(seed).stream("pong_delay")), min_(min_delay_us), max_(max_delay_us) {}
  std::string name() const override { return "pong"; }
  void start(Executor& executor, Bus& bus) override {
    bus.subscribe<a3lcm::link_message_t>(
        kPing, [this, &executor, &bus](const a3lcm::link_message_t& ping, int64_t) {
          const int64_t delay =
              min_ + static_cast<int64_t>(rng_.uniform(0.0, static_cast<double>(max_ - min_)));
          executor.schedule_after(delay, [ping, &executor, &bus] {
            a3lcm::link_message_t pong = ping;
            pong.utime_us = executor.clock().now_us();
            pong.sender = "pong";
            pong.kind = "pong";
            bus.publish(kPong, pong);
          });
          ++answered_;
        });
  }
  int answered() const { return answered_; }

 private:
  Rng rng_;
  int64_t min_, max_;
  std::atomic<int> answered_{0};
};

TEST(VirtualRuntime, TwoNodesExchangeMessagesWithExactVirtualTiming) {
  VirtualRuntime runtime;
  PingNode ping(10'000);
  PongNode pong(1, 3'000, 3'000);
  runtime.add(ping);
  runtime.add(pong);
  runtime.run_until(100'000);
  EXPECT_EQ(runtime.clock().now_us(), 100'000);

  std::vector<Event> expected;
  for (int64_t k = 1; k <= 10; ++k) {
    expected.push_back({10'000 * k, "ping", k});
    if (k <= 9) expected.push_back({10'000 * k + 3'000, "pong rtt=3000", k});
  }
  EXPECT_EQ(ping.events(), expected);
  EXPECT_EQ(pong.answered(), 10) << "the 10th ping was answered; its pong is still pending";
  EXPECT_EQ(runtime.bus().decode_failures(), 0u);

  // Continuing the run delivers the pending pong at 103 ms.
  runtime.run_until(105'000);
  const auto events = ping.events();
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back(), (Event{103'000, "pong rtt=3000", 10}));
}

std::vector<Event> run_jittered(uint64_t seed) {
  VirtualRuntime runtime;
  PingNode ping(2'000);
  PongNode pong(seed, 500, 9'000);  // delays longer than the period: pongs overtake
  runtime.add(ping);
  runtime.add(pong);
  runtime.run_until(500'000);
  return ping.events();
}

TEST(VirtualRuntime, SameSeedGivesTheSameRunDifferentSeedADifferentOne) {
  const std::vector<Event> a = run_jittered(7);
  const std::vector<Event> b = run_jittered(7);
  ASSERT_GT(a.size(), 400u);
  EXPECT_EQ(a, b);
  EXPECT_NE(run_jittered(8), a);

  // The jitter really reorders: some pong arrives after a later ping's pong.
  bool overtaken = false;
  int64_t last_pong_id = 0;
  for (const auto& e : a) {
    if (e.what.rfind("pong", 0) != 0) continue;
    if (e.id < last_pong_id) overtaken = true;
    last_pong_id = e.id;
  }
  EXPECT_TRUE(overtaken);
}

// A node that pings itself over its own bus: exercises RealTimeNodeThread end to end.
class SelfPingNode final : public Node {
 public:
  std::string name() const override { return "self_ping"; }
  void start(Executor& executor, Bus& bus) override {
    bus.subscribe<a3lcm::link_message_t>(
        kPing, [this](const a3lcm::link_message_t& m, int64_t) { received_ = m.message_id; });
    executor.schedule_every(5'000, [&bus, this] {
      a3lcm::link_message_t m{};
      m.message_id = ++sent_;
      bus.publish(kPing, m);
    });
  }
  std::atomic<int64_t> received_{0};

 private:
  int64_t sent_ = 0;
};

TEST(RealTimeNodeThread, RunsANodeOnItsOwnThreadUntilStopped) {
  const WallClock clock;
  SelfPingNode node;
  RealTimeNodeThread thread(node, clock, "memq://");
  EXPECT_EQ(thread.bus().url(), "memq://");
  thread.start();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (node.received_.load() < 5 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  test::DeadlineThread stopper([&] { thread.stop_and_join(); });
  EXPECT_TRUE(stopper.join_within(std::chrono::seconds(3), [&] { thread.executor().stop(); }));
  EXPECT_GE(node.received_.load(), 5) << "messages went round the node's own bus";
  EXPECT_EQ(thread.failure(), "");
}

TEST(RealTimeNodeThread, StopRightAfterStartDoesNotHang) {
  const WallClock clock;
  for (int i = 0; i < 50; ++i) {
    SelfPingNode node;
    RealTimeNodeThread thread(node, clock, "memq://");
    thread.start();
    test::DeadlineThread stopper([&] { thread.stop_and_join(); });
    ASSERT_TRUE(stopper.join_within(std::chrono::seconds(2), [&] { thread.executor().stop(); }))
        << "iteration " << i;
  }
}

class ThrowingNode final : public Node {
 public:
  std::string name() const override { return "thrower"; }
  void start(Executor& executor, Bus&) override {
    executor.schedule_after(2'000, [] { throw std::runtime_error("sensor table missing"); });
  }
};

TEST(RealTimeNodeThread, AnExceptionEndsTheThreadAndIsReported) {
  const WallClock clock;
  ThrowingNode node;
  RealTimeNodeThread thread(node, clock, "memq://");
  const LogLevel saved = log_level();
  set_log_level(LogLevel::kOff);
  thread.start();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (thread.failure().empty() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  set_log_level(saved);
  EXPECT_EQ(thread.failure(), "sensor table missing");
  thread.stop_and_join();
}

}  // namespace
}  // namespace a3::common
