// The bridge node on its own in virtual time: sensor rates against the state rate, seeded
// noise, bad states, ESC frames to A3_ACTUATORS, commands forwarded one for one (and no
// heartbeats of its own), status to A3_FC_STATUS with the reason text, NodeStatus.
#include <gtest/gtest.h>

#include <cmath>

#include "bridge/sim/bridge_node.hpp"
#include "tests/bridge_nodes/node_harness.hpp"

namespace a3::bridge {
namespace {

using a3::test::CanPeer;
using a3::test::LcmRecorder;
using a3::test::StatePublisher;

struct BridgeRig {
  explicit BridgeRig(double state_rate_hz, BridgeNodeConfig config = {},
                     std::function<a3lcm::vehicle_state_t(int64_t)> state_at = a3::test::resting_state)
      : can(rt.scheduler()),
        port(can.attach("bridge")),
        peer(can, 10),
        states(state_rate_hz, std::move(state_at)),
        bridge(*port, config) {
    rt.add(states);
    rt.add(recorder);
    rt.add(bridge);
    peer.start(rt.scheduler());
  }
  common::VirtualRuntime rt;
  VirtualCanBus can;
  std::unique_ptr<CanBus> port;
  CanPeer peer;
  StatePublisher states;
  LcmRecorder recorder;
  BridgeNode bridge;
};

TEST(BridgeNode, SensorRatesFollowTheScheduleButNeverOutrunTheStates) {
  BridgeRig fast(250.0);  // the rig's dynamics rate
  fast.rt.run_until(2'000'000 - 1);
  EXPECT_EQ(fast.peer.imu.size(), 400u);
  EXPECT_EQ(fast.peer.gnss.size(), 20u);
  EXPECT_EQ(fast.peer.baro.size(), 100u);
  EXPECT_EQ(fast.peer.mag.size(), 100u);
  EXPECT_EQ(fast.peer.battery.size(), 10u);
  // Every report covers the time since the previous one: 4 or 8 ms, 5 ms on average.
  double covered_s = 0.0;
  for (std::size_t i = 1; i < fast.peer.imu.size(); ++i) {
    const float iv = fast.peer.imu[i].msg.integration_interval;
    EXPECT_TRUE(std::abs(iv - 0.004f) < 1e-6 || std::abs(iv - 0.008f) < 1e-6) << iv;
    covered_s += iv;
  }
  EXPECT_NEAR(covered_s, 2.0 - 0.004, 1e-4);

  BridgeRig slow(100.0);  // states slower than the IMU's 200 Hz: one report per state
  slow.rt.run_until(2'000'000 - 1);
  EXPECT_EQ(slow.peer.imu.size(), 200u);
  EXPECT_EQ(slow.bridge.counters().get("states"), 200u);
}

TEST(BridgeNode, SensorNoiseIsSeeded) {
  BridgeNodeConfig a, b;
  a.seed = 7;
  b.seed = 8;
  BridgeRig one(250.0, a), two(250.0, a), other(250.0, b);
  for (BridgeRig* r : {&one, &two, &other}) r->rt.run_until(1'000'000);
  ASSERT_EQ(one.peer.imu.size(), two.peer.imu.size());
  for (std::size_t i = 0; i < one.peer.imu.size(); ++i) EXPECT_EQ(one.peer.imu[i].msg, two.peer.imu[i].msg);
  EXPECT_NE(one.peer.imu[10].msg, other.peer.imu[10].msg);
  // The accelerometer's noise has the model's standard deviation (0.03 m/s², float16 aside).
  double sum = 0, sum2 = 0;
  for (const auto& r : one.peer.imu) {
    const double x = r.msg.accelerometer_latest[0];
    sum += x;
    sum2 += x * x;
  }
  const double n = static_cast<double>(one.peer.imu.size());
  EXPECT_NEAR(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 0.03, 0.005);
}

TEST(BridgeNode, DropsBadStatesAndCountsThem) {
  BridgeRig rig(250.0, {}, [](int64_t t_us) {
    a3lcm::vehicle_state_t s = a3::test::resting_state(t_us);
    if (t_us == 400'000) s.p_W_m[0] = std::nan("");
    if (t_us == 800'000) s.q_WB[0] = 0.2;  // not a rotation
    return s;
  });
  rig.rt.run_until(999'999);
  EXPECT_EQ(rig.bridge.counters().get("states_rejected"), 2u);
  EXPECT_EQ(rig.bridge.counters().get("states"), 248u);
  for (const auto& g : rig.peer.gnss) EXPECT_NE(g.msg.timestamp.usec, 400'000u);
}

TEST(BridgeNode, EscFramesBecomeActuatorCommands) {
  BridgeRig rig(250.0);
  rig.rt.run_until(100'000);
  EscRawCommand esc;
  esc.cmd = {8191, 4096, 0, -5};
  rig.peer.publish(esc);
  esc.cmd = {0, 0, 0, 0};
  rig.peer.publish(esc);
  esc.cmd = {100, 100, 100};  // three rotors: not this vehicle
  rig.peer.publish(esc);
  rig.rt.run_until(110'000);
  ASSERT_EQ(rig.recorder.actuators.size(), 2u);
  const auto& a = rig.recorder.actuators[0];
  EXPECT_DOUBLE_EQ(a.throttle[0], 1.0);
  EXPECT_NEAR(a.throttle[1], 0.5, 1e-4);
  EXPECT_DOUBLE_EQ(a.throttle[2], 0.0);
  EXPECT_DOUBLE_EQ(a.throttle[3], 0.0);  // reverse taken as stop
  EXPECT_TRUE(a.armed);
  EXPECT_GT(a.utime_us, 100'000);
  EXPECT_FALSE(rig.recorder.actuators[1].armed);  // all zero: disarmed
  EXPECT_EQ(rig.bridge.counters().get("esc_clamped"), 1u);
  EXPECT_EQ(rig.bridge.counters().get("esc_rejected"), 1u);
}

TEST(BridgeNode, ForwardsCommandsOneForOneAndMakesNoHeartbeatsOfItsOwn) {
  BridgeRig rig(250.0);
  rig.rt.run_until(5'000'000);
  EXPECT_TRUE(rig.peer.commands.empty());  // five seconds of silence from the ground: silence on CAN
  a3lcm::fc_command_t c{};
  c.seq = 5;
  c.command = a3lcm::fc_command_t::GOTO;
  c.target_W_m[0] = 10;
  c.target_W_m[1] = -20;
  c.target_W_m[2] = 30;
  c.speed_limit_mps = 4;
  c.yaw_deg = 45;
  rig.recorder.command(c);
  c.seq = 5;
  c.command = a3lcm::fc_command_t::HEARTBEAT;
  rig.recorder.command(c);
  rig.rt.run_until(5'010'000);
  ASSERT_EQ(rig.peer.commands.size(), 2u);
  const FcCommand& got = rig.peer.commands[0].msg;
  EXPECT_EQ(got.seq, 5);
  EXPECT_EQ(got.command, FcCommand::kGoto);
  EXPECT_FLOAT_EQ(got.target_W_m[1], -20.0f);
  EXPECT_FLOAT_EQ(got.speed_limit_mps, 4.0f);
  EXPECT_FLOAT_EQ(got.yaw_deg, 45.0f);
  EXPECT_EQ(rig.peer.commands[1].msg.command, FcCommand::kHeartbeat);
  EXPECT_EQ(rig.peer.commands[0].source, 20);
}

TEST(BridgeNode, StatusFramesBecomeFcStatusWithTheReasonText) {
  BridgeRig rig(250.0);
  rig.rt.run_until(100'000);
  FcStatus s;
  s.mode = FcStatus::kModeHold;
  s.armed = true;
  s.last_command_seq = 3;
  s.last_command_accepted = false;
  s.last_command_reason = FcStatus::kReasonOutsideGeofence;
  rig.peer.publish(s);
  s.last_command_reason = 99;  // a code this bridge does not know
  rig.peer.publish(s);
  rig.rt.run_until(110'000);
  ASSERT_EQ(rig.recorder.statuses.size(), 2u);
  EXPECT_EQ(rig.recorder.statuses[0].mode, int8_t{a3lcm::fc_status_t::HOLD});
  EXPECT_EQ(rig.recorder.statuses[0].last_command_reason, "outside the geofence");
  EXPECT_EQ(rig.recorder.statuses[1].last_command_reason, "unknown reason code");
}

TEST(BridgeNode, NodeStatusWarnsWhenStatesStop) {
  BridgeRig rig(250.0);
  rig.rt.run_until(3'000'000);
  ASSERT_GE(rig.peer.node_status.size(), 3u);
  EXPECT_EQ(rig.peer.node_status.back().source, 20);
  EXPECT_EQ(rig.peer.node_status.back().msg.health, NodeStatus::kHealthOk);
  rig.states.enabled = false;
  rig.rt.run_until(5'500'000);
  EXPECT_EQ(rig.peer.node_status.back().msg.health, NodeStatus::kHealthWarning);
  EXPECT_NEAR(static_cast<double>(rig.peer.node_status.size()), 6.0, 1.0);  // 1 Hz
}

}  // namespace
}  // namespace a3::bridge
