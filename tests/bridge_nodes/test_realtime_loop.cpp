// The same nodes on the real-time runtime: dynamics, bridge, fc and a ground station each in
// its own thread with its own LCM (udpm, a port of this test's own), the bridge and the fc on
// the userspace CAN bus, all on the wall clock. Generous bounds, behaviour only (CONVENTIONS.md):
// it takes off to 4 m, holds, lands and disarms. Skipped where LCM multicast does not loop back.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "bridge/can/userspace_bus.hpp"
#include "tests/bridge_nodes/closed_loop.hpp"

namespace a3::bridge {
namespace {

constexpr int8_t kHold = a3lcm::fc_status_t::HOLD;
constexpr int8_t kDisarmed = a3lcm::fc_status_t::DISARMED;

// A thread-safe view of the ground station (its callbacks run on its own thread).
struct Shared {
  std::mutex mutex;
  a3lcm::fc_status_t status{};
  a3lcm::vehicle_state_t state{};
  uint64_t statuses = 0;
};

TEST(RealTimeLoop, TakesOffHoldsAndLandsOnTheWallClock) {
  const std::string url = "udpm://239.255.76.67:" + std::to_string(7700 + ::getpid() % 200) + "?ttl=0";
  const std::filesystem::path can_root = std::filesystem::path("/tmp") / ("a3-fcloop-" + std::to_string(::getpid()));
  std::filesystem::remove_all(can_root);
  UserspaceCanOptions can_options;
  can_options.root = can_root;
  UserspaceCanBus fc_can("fcloop", can_options), bridge_can("fcloop", can_options);

  dynamics::DynamicsNodeConfig dc;
  dc.publish_rate_hz = 250.0;
  dynamics::DynamicsNode dynamics(dc);
  BridgeNode bridge(bridge_can, BridgeNodeConfig{});
  FcNodeConfig fc_config;
  fc_config.params.vehicle = rigs::fc_vehicle_from_airframe(dc.params);
  FcNode fc(fc_can, fc_config);
  a3::test::GroundStation ground;
  Shared shared;
  ground.on_status = [&](const a3lcm::fc_status_t& s) {
    std::lock_guard<std::mutex> lock(shared.mutex);
    shared.status = s;
    ++shared.statuses;
  };
  ground.on_state = [&](const a3lcm::vehicle_state_t& s) {
    std::lock_guard<std::mutex> lock(shared.mutex);
    shared.state = s;
  };

  const common::WallClock clock(1.0);
  std::vector<std::unique_ptr<common::RealTimeNodeThread>> threads;
  try {
    for (common::Node* n : std::initializer_list<common::Node*>{&ground, &dynamics, &bridge, &fc}) {
      threads.push_back(std::make_unique<common::RealTimeNodeThread>(*n, clock, url));
    }
    threads.front()->bus().check_loopback();
  } catch (const std::exception& e) {
    GTEST_SKIP() << "LCM over " << url << " does not work here: " << e.what();
  }
  for (auto& t : threads) t->start();
  const auto wait_for = [&](double timeout_s, const std::function<bool(const a3lcm::fc_status_t&,
                                                                       const a3lcm::vehicle_state_t&)>& pred) {
    const double end = clock.now_s() + timeout_s;
    while (clock.now_s() < end) {
      {
        std::lock_guard<std::mutex> lock(shared.mutex);
        if (shared.statuses > 0 && pred(shared.status, shared.state)) return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  };
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_TRUE(wait_for(3.0, [](const auto&, const auto&) { return true; })) << "no status from the fc";
  const int32_t seq = ground.command(a3lcm::fc_command_t::TAKEOFF, 0, 0, 4.0);
  EXPECT_TRUE(wait_for(2.0, [&](const auto& s, const auto&) { return s.last_command_seq == seq && s.last_command_accepted; }));
  EXPECT_TRUE(wait_for(12.0, [](const auto& s, const auto& v) { return s.mode == kHold && std::abs(v.p_W_m[2] - 4.0) < 0.5; }))
      << "z = " << shared.state.p_W_m[2];
  std::this_thread::sleep_for(std::chrono::seconds(2));
  {
    std::lock_guard<std::mutex> lock(shared.mutex);
    EXPECT_NEAR(shared.state.p_W_m[2], 4.0, 0.5);
    EXPECT_EQ(shared.status.mode, kHold);
  }
  ground.command(a3lcm::fc_command_t::LAND);
  EXPECT_TRUE(wait_for(15.0, [](const auto& s, const auto& v) { return s.mode == kDisarmed && v.on_ground; }))
      << "z = " << shared.state.p_W_m[2];
  for (auto& t : threads) t->stop_and_join();
  fc.stop();
  bridge.stop();
  for (auto& t : threads) EXPECT_EQ(t->failure(), "");
  EXPECT_EQ(fc.counters().get("sensor_rejected"), 0u);
  EXPECT_EQ(fc_can.stats().send_refused + bridge_can.stats().send_refused, 0u);
  const auto lateness = threads[3]->executor().lateness_samples_us();
  std::vector<double> sorted = lateness;
  std::sort(sorted.begin(), sorted.end());
  if (!sorted.empty()) {
    std::cout << "fc timer lateness: p50 " << sorted[sorted.size() / 2] << " us, p99 "
              << sorted[sorted.size() * 99 / 100] << " us\n";
  }
  std::filesystem::remove_all(can_root);
}

}  // namespace
}  // namespace a3::bridge
