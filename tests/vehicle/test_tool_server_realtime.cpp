// The tool server unchanged on the real-time runtime: on its own thread with a real LCM bus
// (memq://), the wall clock at 10× real time, the fake fc and the probe sharing its thread.
// Checks are about behaviour (answers, their order, the flight, the fc-status timeout) with
// generous bounds.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "common/clock.hpp"
#include "common/runtime.hpp"
#include "tests/vehicle/vehicle_test_util.hpp"

namespace a3::vehicle {
namespace {

using test::mcp;

void wait_until(const common::Clock& clock, int64_t t_us) {
  while (clock.now_us() < t_us) std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

// Publishes the action on the node thread's bus at simulated time t_s.
void send_at(common::RealTimeNodeThread& thread, double t_s, int turn, const nlohmann::json& action) {
  common::Bus& bus = thread.bus();
  common::Executor& executor = thread.executor();
  executor.schedule_at(static_cast<int64_t>(t_s * 1e6), [&bus, &executor, turn, action] {
    bus.publish(common::channels::kLinkUpRx.of(0), agent::encode_action({turn, 0, action}, turn, executor.clock().now_us(), "agent"));
  });
}

TEST(ToolServerRealTime, FliesARouteOnItsOwnThreadWithARealBus) {
  ToolServerNode server(test::test_config());
  test::FakeFlightController fc;
  test::Probe probe(test::SliceResponder::kAccept);
  const common::WallClock clock(10.0);
  common::RealTimeNodeThread thread(server, clock, "memq://");
  fc.start(thread.executor(), thread.bus());
  probe.start(thread.executor(), thread.bus());
  send_at(thread, 0.5, 1, mcp("takeoff", {{"altitude_m", 20.0}}));
  send_at(thread, 13.0, 2, mcp("navigate_to", {{"waypoints", {{40, 20, 20}, {40, 40, 20}}}}));
  send_at(thread, 13.0, 3, mcp("read_telemetry"));
  thread.start();
  wait_until(clock, 30'000'000);  // 3 s of wall time
  thread.stop_and_join();
  ASSERT_EQ(thread.failure(), "");

  ASSERT_EQ(probe.down.size(), 3u);
  EXPECT_EQ(probe.down[0].obs["result"]["status"], "accepted");
  EXPECT_EQ(probe.down[1].obs["tool"], "navigate_to");
  EXPECT_EQ(probe.down[1].obs["result"]["status"], "accepted");
  EXPECT_EQ(probe.down[2].obs["tool"], "read_telemetry") << "after the route's answer";
  EXPECT_EQ(probe.down[2].obs["result"]["mode"], "goto");
  EXPECT_LT(probe.down[1].t_s - 13.0, 1.0) << "answered promptly (simulated seconds at 10x)";
  EXPECT_LT((fc.position() - Eigen::Vector3d(40, 40, 20)).norm(), 1e-6) << fc.position().transpose();
  EXPECT_EQ(server.counters().get("routes_completed"), 1u);
  EXPECT_EQ(server.counters().get("fc_commands"), 3u);
}

TEST(ToolServerRealTime, TimesOutOnTheWallClockWhenTheFcIsSilent) {
  ToolServerNode server(test::test_config());
  test::FakeFcConfig dead;
  dead.answer_commands = false;
  test::FakeFlightController fc(dead);
  test::Probe probe(test::SliceResponder::kSilent);
  const common::WallClock clock(10.0);
  common::RealTimeNodeThread thread(server, clock, "memq://");
  fc.start(thread.executor(), thread.bus());
  probe.start(thread.executor(), thread.bus());
  send_at(thread, 1.0, 1, mcp("hold"));
  send_at(thread, 1.0, 2, mcp("switch_network_slice", {{"slice", "URLLC"}}));
  thread.start();
  wait_until(clock, 8'000'000);
  thread.stop_and_join();
  ASSERT_EQ(thread.failure(), "");
  ASSERT_EQ(probe.down.size(), 2u);
  EXPECT_EQ(probe.down[0].obs["result"]["status"], "timeout");
  EXPECT_NEAR(probe.down[0].t_s, 3.0, 0.5) << "2 s after the command";
  EXPECT_EQ(probe.down[1].obs["result"]["status"], "timeout");
  EXPECT_NEAR(probe.down[1].t_s, 5.0, 0.5) << "queued behind the first, then 2 s";
}

}  // namespace
}  // namespace a3::vehicle
