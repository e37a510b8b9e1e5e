// Only the commanders command (issue 14): the fc obeys a3.fc.Command only from its command
// sources (the bridge, node 20), refuses the rest, counts them and reports them in
// a3.fc.CommandRefused at most once a second, which the bridge turns into "command_refused"
// safety events; the bridge takes ESC commands and fc status only from the fc (node 10).
// A spoofing node (99) on the same virtual CAN bus injects the faults.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "a3lcm/safety_event_t.hpp"
#include "bridge/nodes/command_sources.hpp"
#include "bridge/nodes/fc_node.hpp"
#include "bridge/sim/bridge_node.hpp"
#include "common/virtual_scheduler.hpp"
#include "tests/bridge_nodes/node_harness.hpp"

namespace a3::bridge {
namespace {

using a3::test::CanPeer;

constexpr uint8_t kSpooferNodeId = 99;

struct SpoofedRig {
  explicit SpoofedRig(FcNodeConfig config = {})
      : can(rt.scheduler()),
        bridge_port(can.attach("bridge")),
        fc_port(can.attach("fc")),
        spoofer(can, kSpooferNodeId),
        states(250.0),
        bridge(*bridge_port, BridgeNodeConfig{}),
        fc(*fc_port, config) {
    rt.add(states);
    rt.add(recorder);
    rt.add(bridge);
    rt.add(fc);
    spoofer.start(rt.scheduler());
    rt.bus().subscribe<a3lcm::safety_event_t>(common::channels::kSafety.of(0), [this](const a3lcm::safety_event_t& e, int64_t) {
      safety.push_back(e);
    });
  }
  // Through the bridge, as the ground commands.
  void ground_command(int8_t kind, double z = 0.0) {
    a3lcm::fc_command_t c{};
    c.seq = ++ground_seq;
    c.command = kind;
    c.target_W_m[2] = z;
    c.yaw_deg = std::nan("");
    recorder.command(c);
  }
  // Straight onto the CAN bus from node 99.
  void spoofed_command(uint8_t kind) {
    FcCommand c;
    c.seq = ++spoofer_seq;
    c.command = kind;
    c.yaw_deg = std::nanf("");
    ASSERT_TRUE(spoofer.publish(c));
  }
  void take_off() {
    rt.run_until(1'000'000);
    ground_command(a3lcm::fc_command_t::ARM);
    rt.run_until(1'100'000);
    ground_command(a3lcm::fc_command_t::TAKEOFF, 5.0);
    rt.run_until(1'200'000);
    ASSERT_EQ(fc.status_snapshot().mode, FcMode::kTakeoff);
  }
  double safety_value_sum(const std::string& source) const {
    double sum = 0.0;
    for (const auto& e : safety) sum += e.source == source ? e.value : 0.0;
    return sum;
  }

  common::VirtualRuntime rt;
  VirtualCanBus can;
  std::unique_ptr<CanBus> bridge_port, fc_port;
  CanPeer spoofer;
  a3::test::StatePublisher states;
  a3::test::LcmRecorder recorder;
  BridgeNode bridge;
  FcNode fc;
  std::vector<a3lcm::safety_event_t> safety;
  int32_t ground_seq = 0, spoofer_seq = 1000;
};

TEST(CommandSources, AnEmergencyStopFromAStrayNodeIsRefusedAndOneFromTheBridgeObeyed) {
  SpoofedRig rig;
  rig.take_off();
  rig.spoofed_command(FcCommand::kEmergencyStop);
  rig.rt.run_until(1'300'000);
  EXPECT_EQ(rig.fc.status_snapshot().mode, FcMode::kTakeoff);
  EXPECT_TRUE(rig.fc.status_snapshot().armed);
  EXPECT_EQ(rig.fc.counters().get("commands_rejected_source"), 1u);
  EXPECT_EQ(rig.fc.counters().get("commands"), 2u);  // the ground's ARM and TAKEOFF only
  EXPECT_EQ(rig.fc.counters().get("refusal_reports"), 1u);
  ASSERT_EQ(rig.safety.size(), 1u);
  const a3lcm::safety_event_t& e = rig.safety[0];
  EXPECT_EQ(e.kind, "command_refused");
  EXPECT_EQ(e.source, "fc");
  EXPECT_EQ(e.value, 1.0);
  EXPECT_NE(e.detail.find("a3.fc.Command 8 (emergency stop, seq 1001) from CAN node 99"), std::string::npos)
      << e.detail;
  EXPECT_NEAR(e.utime_us, 1'200'000, 10'000);  // at once (CAN queueing aside), not 1 s later

  rig.ground_command(a3lcm::fc_command_t::EMERGENCY_STOP);
  rig.rt.run_until(1'400'000);
  EXPECT_EQ(rig.fc.status_snapshot().mode, FcMode::kEmergency);
  EXPECT_EQ(rig.fc.counters().get("commands_rejected_source"), 1u);
}

TEST(CommandSources, AFloodOfSpoofedCommandsGivesAtMostOneSafetyEventASecondAndCountsThemAll) {
  SpoofedRig rig;
  rig.take_off();
  // 20 ms apart for 2 s: 100 emergency stops.
  for (int k = 0; k < 100; ++k) {
    rig.spoofed_command(FcCommand::kEmergencyStop);
    rig.rt.run_until(1'200'000 + (k + 1) * 20'000);
  }
  rig.rt.run_until(4'500'000);  // the last batch's report is due 1 s after the previous one
  EXPECT_EQ(rig.fc.status_snapshot().mode, FcMode::kTakeoff);
  EXPECT_EQ(rig.fc.counters().get("commands_rejected_source"), 100u);
  EXPECT_EQ(rig.safety.size(), 3u);  // at 1.2 s (the first), 2.2 s, 3.2 s
  EXPECT_EQ(rig.safety_value_sum("fc"), 100.0);
  for (std::size_t i = 1; i < rig.safety.size(); ++i) {
    EXPECT_GE(rig.safety[i].utime_us - rig.safety[i - 1].utime_us, 990'000);  // 1 s at the fc, CAN queueing aside
  }
  EXPECT_NE(rig.safety.back().detail.find("100 in all"), std::string::npos) << rig.safety.back().detail;
}

TEST(CommandSources, AGroundStationNodeCanBeACommandSourceToo) {
  FcNodeConfig config;
  config.command_sources = {kDefaultBridgeNodeId, kSpooferNodeId};
  SpoofedRig rig(config);
  rig.take_off();
  rig.spoofed_command(FcCommand::kEmergencyStop);
  rig.rt.run_until(1'300'000);
  EXPECT_EQ(rig.fc.status_snapshot().mode, FcMode::kEmergency);
  EXPECT_EQ(rig.fc.counters().get("commands_rejected_source"), 0u);
  EXPECT_TRUE(rig.safety.empty());
}

TEST(CommandSources, ABadListOfSourcesIsRefusedWhenTheNodeIsMade) {
  EXPECT_THROW(check_command_sources({}, 10), std::invalid_argument);
  EXPECT_THROW(check_command_sources({20, 10}, 10), std::invalid_argument);
  EXPECT_THROW(check_command_sources({0}, 10), std::invalid_argument);
  EXPECT_THROW(check_command_sources({128}, 10), std::invalid_argument);
  EXPECT_NO_THROW(check_command_sources({20, 21}, 10));
  EXPECT_EQ(command_sources_text({20, 21}), "20, 21");
}

TEST(CommandSources, EscCommandsFromANodeThatIsNotTheFcDoNotReachTheVehicle) {
  SpoofedRig rig;
  rig.rt.run_until(1'000'000);
  const std::size_t actuators_before = rig.recorder.actuators.size();
  EscRawCommand full;
  full.cmd = {8191, 8191, 8191, 8191};
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(rig.spoofer.publish(full));
    rig.rt.run_until(1'000'000 + (k + 1) * 10'000);
  }
  rig.rt.run_until(1'500'000);
  // The fc's own zeros went on at 250 Hz; none of the spoofer's full throttles got through.
  EXPECT_GT(rig.recorder.actuators.size(), actuators_before);
  for (const auto& a : rig.recorder.actuators) EXPECT_FALSE(a.armed);
  EXPECT_EQ(rig.bridge.counters().get("rejected_source"), 10u);
  ASSERT_EQ(rig.safety.size(), 1u);  // the first at once; the other nine wait for the interval
  EXPECT_EQ(rig.safety[0].source, "bridge");
  EXPECT_NE(rig.safety[0].detail.find("uavcan.equipment.esc.RawCommand from CAN node 99"), std::string::npos)
      << rig.safety[0].detail;
  rig.rt.run_until(2'500'000);
  EXPECT_EQ(rig.safety_value_sum("bridge"), 10.0);
}

TEST(RefusalReports, TheFirstAtOnceThenOneReportPerIntervalCoveringAllSinceThePrevious) {
  common::VirtualScheduler executor;
  std::vector<std::pair<int64_t, uint64_t>> reports;  // (time, refusals covered)
  RefusalReports refusals(1'000'000, [&](uint64_t n, uint64_t) { reports.emplace_back(executor.clock().now_us(), n); });
  refusals.start(executor);
  executor.run_until(500'000);
  refusals.record();
  executor.run_until(600'000);
  for (int k = 0; k < 5; ++k) refusals.record();
  executor.run_until(3'000'000);
  refusals.record();  // long after: at once again
  executor.run_until(3'000'001);
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_EQ(reports[0], std::make_pair(int64_t{500'000}, uint64_t{1}));
  EXPECT_EQ(reports[1], std::make_pair(int64_t{1'500'000}, uint64_t{5}));
  EXPECT_EQ(reports[2], std::make_pair(int64_t{3'000'000}, uint64_t{1}));
  EXPECT_EQ(refusals.total(), 7u);
  EXPECT_THROW(RefusalReports(0, [](uint64_t, uint64_t) {}), std::invalid_argument);
}

TEST(RefusalReports, StopCancelsTheReportThatWaits) {
  common::VirtualScheduler executor;
  int reports = 0;
  RefusalReports refusals(1'000'000, [&](uint64_t, uint64_t) { ++reports; });
  refusals.start(executor);
  refusals.record();
  executor.run_until(10);
  refusals.record();
  refusals.stop();
  executor.run_until(5'000'000);
  EXPECT_EQ(reports, 1);
}

}  // namespace
}  // namespace a3::bridge
