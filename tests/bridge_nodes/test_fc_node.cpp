// The fc node on its CAN bus in virtual time, fed by a bridge node from a resting vehicle:
// ESC frames at the control rate (zeros while disarmed), status at its rate and after each
// command, NodeStatus with mode and health, bad frames counted without harm, repeated commands
// not executed twice, and an accepted command reflected in the ESC frames at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "bridge/fc/state_estimator.hpp"
#include "bridge/nodes/fc_node.hpp"
#include "bridge/sim/bridge_node.hpp"
#include "bridge/sim/sensor_frames.hpp"
#include "tests/bridge_nodes/node_harness.hpp"

namespace a3::bridge {
namespace {

using a3::test::CanPeer;

struct FcRig {
  explicit FcRig(FcNodeConfig config = {})
      : can(rt.scheduler()),
        bridge_port(can.attach("bridge")),
        fc_port(can.attach("fc")),
        peer(can, 30),
        states(250.0),
        bridge(*bridge_port, BridgeNodeConfig{}),
        fc(*fc_port, config) {
    rt.add(states);
    rt.add(recorder);
    rt.add(bridge);
    rt.add(fc);
    peer.start(rt.scheduler());
  }
  int32_t command(int8_t kind, double z = 0.0, int32_t seq = -1) {
    a3lcm::fc_command_t c{};
    c.seq = seq >= 0 ? seq : ++seq_;
    c.command = kind;
    c.target_W_m[2] = z;
    c.yaw_deg = std::nan("");
    recorder.command(c);
    return c.seq;
  }
  static bool spinning(const EscRawCommand& e) {
    return std::any_of(e.cmd.begin(), e.cmd.end(), [](int16_t v) { return v > 0; });
  }
  common::VirtualRuntime rt;
  VirtualCanBus can;
  std::unique_ptr<CanBus> bridge_port, fc_port;
  CanPeer peer;
  a3::test::StatePublisher states;
  a3::test::LcmRecorder recorder;
  BridgeNode bridge;
  FcNode fc;
  int32_t seq_ = 0;
};

TEST(FcNode, DisarmedItSendsZerosAtTheControlRateAndReportsItself) {
  FcRig rig;
  rig.rt.run_until(2'000'000);
  EXPECT_NEAR(static_cast<double>(rig.peer.esc.size()), 500.0, 1.0);  // 250 Hz
  for (const auto& e : rig.peer.esc) {
    ASSERT_EQ(e.msg.cmd.size(), 4u);
    EXPECT_FALSE(FcRig::spinning(e.msg));
    EXPECT_EQ(e.source, 10);
  }
  EXPECT_NEAR(static_cast<double>(rig.peer.statuses.size()), 20.0, 1.0);  // 10 Hz
  EXPECT_EQ(rig.peer.statuses.back().msg.mode, FcStatus::kModeDisarmed);
  EXPECT_NEAR(rig.peer.statuses.back().msg.battery_pct, 80.0, 0.01);
  std::vector<NodeStatus> fc_status;
  for (const auto& n : rig.peer.node_status) {
    if (n.source == 10) fc_status.push_back(n.msg);
  }
  ASSERT_GE(fc_status.size(), 2u);
  EXPECT_EQ(fc_status.front().mode, NodeStatus::kModeInitialization);  // at start: no estimate yet
  EXPECT_EQ(fc_status.back().mode, NodeStatus::kModeOperational);
  EXPECT_EQ(fc_status.back().health, NodeStatus::kHealthOk);
  EXPECT_EQ(rig.fc.counters().get("sensor_rejected"), 0u);
}

TEST(FcNode, SilentSensorsMakeItsHealthAWarning) {
  FcRig rig;
  rig.states.enabled = false;
  rig.rt.run_until(2'500'000);
  ASSERT_FALSE(rig.peer.node_status.empty());
  const auto& last = *std::find_if(rig.peer.node_status.rbegin(), rig.peer.node_status.rend(),
                                   [](const auto& n) { return n.source == 10; });
  EXPECT_EQ(last.msg.health, NodeStatus::kHealthWarning);
  EXPECT_EQ(last.msg.mode, NodeStatus::kModeInitialization);
  const int32_t seq = rig.command(a3lcm::fc_command_t::TAKEOFF, 5.0);
  rig.rt.run_until(2'600'000);
  ASSERT_FALSE(rig.recorder.statuses.empty());
  EXPECT_EQ(rig.recorder.statuses.back().last_command_seq, seq);
  EXPECT_EQ(rig.recorder.statuses.back().last_command_reason, "no position estimate");
}

TEST(FcNode, BadFramesAndUnusableSensorValuesAreCountedNotFollowed) {
  FcRig rig;
  rig.rt.run_until(1'000'000);
  // A RawIMU full of NaN from another node, a Fix2 without a fix, garbage frames.
  AhrsRawImu nan_imu;
  nan_imu.accelerometer_latest = {std::numeric_limits<float>::quiet_NaN(), 0, 0};
  rig.peer.publish(nan_imu);
  GnssFix2 no_fix;
  no_fix.status = GnssFix2::kStatusNoFix;
  rig.peer.publish(no_fix);
  CanFrame garbage;
  garbage.id = 0x10000000u | (1003u << 8) | 30u;  // RawIMU from node 30
  garbage.size = 8;
  garbage.data = {0x12, 0x34, 1, 2, 3, 4, 5, 0x83};  // the start of a transfer (id 3) that never ends
  rig.peer.send_raw(garbage);
  garbage.size = 3;
  garbage.data = {0x01, 0x02, 0x64};  // the end of a transfer (id 4) that never started
  rig.peer.send_raw(garbage);
  CanFrame empty;
  empty.id = garbage.id;
  empty.size = 0;  // no tail byte at all
  rig.peer.send_raw(empty);
  const std::size_t esc_before = rig.peer.esc.size();
  rig.rt.run_until(4'000'000);
  EXPECT_EQ(rig.fc.counters().get("sensor_rejected"), 2u);
  const ReassemblerStats& rs = rig.fc.dronecan().reassembler_stats();
  EXPECT_EQ(rs.rejected_frames(), 2u);  // the end without a start, the frame without a tail byte
  EXPECT_EQ(rs.expired_transfers, 1u);  // the start that never ended, swept after 2 s
  EXPECT_NEAR(static_cast<double>(rig.peer.esc.size() - esc_before), 750.0, 1.0);  // it kept running its loop
  EXPECT_EQ(rig.peer.statuses.back().msg.mode, FcStatus::kModeDisarmed);
}

TEST(FcNode, ARepeatedCommandIsNotExecutedTwice) {
  FcRig rig;
  rig.rt.run_until(1'000'000);
  const int32_t seq = rig.command(a3lcm::fc_command_t::TAKEOFF, 5.0);
  rig.rt.run_until(1'100'000);
  rig.command(a3lcm::fc_command_t::TAKEOFF, 5.0, seq);  // the ground retransmits
  rig.rt.run_until(1'200'000);
  const auto& c = rig.fc.counters();
  EXPECT_EQ(c.get("commands_repeated"), 1u);
  EXPECT_EQ(c.get("commands_refused"), 0u);
  // Both got a status at once (besides the 10 Hz ones): the reply does not wait for the next.
  int replies = 0;
  for (const auto& s : rig.recorder.statuses) replies += s.last_command_seq == seq;
  EXPECT_GE(replies, 2);
}

// The delay from the command's arrival on the bus to the first ESC frame that spins the rotors,
// for a command published at 1 s + phase_us.
double command_to_esc_delay_us(bool step_on_command, int64_t phase_us) {
  FcNodeConfig config;
  config.step_on_command = step_on_command;
  FcRig rig(config);
  rig.rt.run_until(1'000'000 + phase_us);
  rig.command(a3lcm::fc_command_t::TAKEOFF, 5.0);
  rig.rt.run_until(1'030'000);
  EXPECT_EQ(rig.peer.commands.size(), 1u);
  const auto first = std::find_if(rig.peer.esc.begin(), rig.peer.esc.end(),
                                  [](const auto& e) { return FcRig::spinning(e.msg); });
  if (rig.peer.commands.empty() || first == rig.peer.esc.end()) return -1.0;
  return static_cast<double>(first->t_us - rig.peer.commands[0].t_us);
}

TEST(FcNode, AnAcceptedCommandReachesTheEscsWithoutWaitingForTheNextTick) {
  // Commands at phases across the 4 ms control period: at once, the delay is the ESC frame's
  // wire time (and a frame in progress); on the tick alone, up to a period.
  double at_once_max = 0.0, tick_sum = 0.0, tick_max = 0.0;
  const int phases = 8;
  for (int k = 0; k < phases; ++k) {
    const double a = command_to_esc_delay_us(true, 500 * k + 100);
    const double b = command_to_esc_delay_us(false, 500 * k + 100);
    ASSERT_GE(a, 0.0);
    ASSERT_GE(b, 0.0);
    at_once_max = std::max(at_once_max, a);
    tick_sum += b;
    tick_max = std::max(tick_max, b);
  }
  std::cout << "command on the bus -> first ESC frame reflecting it, virtual bus: at most " << at_once_max
            << " us (step on command); mean " << tick_sum / phases << " us, at most " << tick_max
            << " us (next control tick)\n";
  EXPECT_LT(at_once_max, 600.0);
  EXPECT_GT(tick_sum / phases, 1000.0);
  EXPECT_GT(tick_max, 2500.0);
}


// A RawIMU at rest or turning at yaw_rate_radps (FLU), covering interval_s.
AhrsRawImu imu_report(double yaw_rate_radps, double interval_s) {
  ImuIntegrator imu;
  imu.add(0.0, Eigen::Vector3d(0, 0, yaw_rate_radps), Eigen::Vector3d(0, 0, 9.80665));
  imu.add(interval_s, Eigen::Vector3d(0, 0, yaw_rate_radps), Eigen::Vector3d(0, 0, 9.80665));
  return imu.take_report(0);
}

TEST(FcNode, ImuReportsThatArriveTogetherAreIntegratedOverTheirOwnIntervals) {
  // 150 ms of IMU reports held up (a stalled sender) then sent at once: the estimator must turn
  // by what the reports say (0.5 rad/s for 150 ms), not by the few milliseconds they took to
  // cross the bus. (30 reports of 7 frames: within the port's 256-frame queue.)
  common::VirtualRuntime rt;
  VirtualCanBus can(rt.scheduler());
  std::unique_ptr<CanBus> port = can.attach("fc");
  CanPeer peer(can, 20);
  FcNode fc(*port, FcNodeConfig{});
  rt.add(fc);
  peer.start(rt.scheduler());
  peer.publish(make_magnetic_field(kEarthFieldGauss * earth_field_direction_W(), 0.0));  // facing east
  for (int k = 1; k <= 40; ++k) {  // at rest, 5 ms apart: the estimator initialises
    rt.run_until(5000 * k);
    peer.publish(imu_report(0.0, 0.005));
  }
  rt.run_until(210'000);
  const double yaw0 = fc.controller().status().yaw_deg;
  rt.run_until(350'000);  // nothing for 140 ms, then 30 reports in one burst
  for (int k = 0; k < 30; ++k) ASSERT_TRUE(peer.publish(imu_report(0.5, 0.005)));
  rt.run_until(500'000);
  const double turned_deg = fc.controller().status().yaw_deg - yaw0;
  std::cout << "a burst of 30 IMU reports of 5 ms at 0.5 rad/s: the estimate turned " << turned_deg
            << " degrees (expected " << 0.5 * 0.15 * 180 / M_PI << ")\n";
  EXPECT_NEAR(yaw0, 0.0, 0.5);
  EXPECT_NEAR(turned_deg, 0.5 * 0.15 * 180 / M_PI, 0.1);
}

}  // namespace
}  // namespace a3::bridge
