// The whole rig in virtual time (the nodes and configuration `a3rig run` builds) with a spoofing
// node on its CAN bus (issue 14): node 99 sends an emergency stop every 0.25 s for 10 s while
// the scripted agent's vehicle flies. The vehicle keeps flying; the fc counts every refused
// command and the episode's recorder lists them as "command_refused" safety events, at most
// one a second. Label "faults".
#include <gtest/gtest.h>

#include <memory>

#include "bridge/can/virtual_can_bus.hpp"
#include "bridge/dronecan/messages.hpp"
#include "common/runtime.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/run/node_configs.hpp"
#include "rigs/run/rig_nodes.hpp"
#include "tests/bridge_nodes/node_harness.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

struct SpoofedVirtualRig {
  explicit SpoofedVirtualRig(const std::string& scenario_name)
      : options(a3::test::virtual_run(scenario_name, "spoofed")),
        scenario(load_scenario_spec(options.scenario, options.shared_dir)),
        configs(make_rig_configs(scenario, options)),
        can(rt.scheduler()),
        can_bridge(can.attach("bridge")),
        can_fc(can.attach("fc")),
        nodes(make_rig_nodes({RigPart::kGround, RigPart::kDynamics, RigPart::kBridge, RigPart::kFc, RigPart::kLinkemu,
                              RigPart::kVehicle},
                             configs, options, scenario, {{can_bridge.get(), can_fc.get()}}, false)),
        spoofer(can, 99) {
    for (common::Node* node : nodes.in_start_order()) rt.add(*node);
    spoofer.start(rt.scheduler());
  }
  // Runs until the vehicle is above altitude_m, at most until limit_s; false when it never got there.
  bool fly_until_above(double altitude_m, double limit_s) {
    for (double t = now_s() + 0.5; t <= limit_s; t += 0.5) {
      rt.run_until(static_cast<int64_t>(t * 1e6));
      if (nodes.recorder->snapshot().last_state.p_W_m[2] > altitude_m) return true;
    }
    return false;
  }
  double now_s() const { return rt.clock().now_s(); }

  RunOptions options;
  Scenario scenario;
  RigConfigs configs;
  common::VirtualRuntime rt;
  bridge::VirtualCanBus can;
  std::unique_ptr<bridge::CanBus> can_bridge, can_fc;
  RigNodes nodes;
  a3::test::CanPeer spoofer;
};

TEST(RigUnderSpoofing, EmergencyStopsFromAStrayNodeDoNotBringTheVehicleDown) {
  SpoofedVirtualRig rig("survey-field");
  ASSERT_TRUE(rig.fly_until_above(5.0, 300.0)) << "the scripted agent's vehicle never climbed above 5 m";
  const double attack_start_s = rig.now_s();
  constexpr int kSpoofed = 40;
  for (int k = 0; k < kSpoofed; ++k) {
    bridge::FcCommand stop;
    stop.seq = 5000 + k;
    stop.command = bridge::FcCommand::kEmergencyStop;
    ASSERT_TRUE(rig.spoofer.publish(stop));
    rig.rt.run_until(static_cast<int64_t>((attack_start_s + 0.25 * (k + 1)) * 1e6));
  }
  rig.rt.run_until(static_cast<int64_t>((rig.now_s() + 2.0) * 1e6));  // the last report is due

  const RecordedEpisode r = rig.nodes.recorder->snapshot();
  EXPECT_FALSE(r.last_state.crashed);
  EXPECT_FALSE(r.last_state.on_ground);
  EXPECT_GT(r.last_state.p_W_m[2], 3.0);
  EXPECT_NE(rig.nodes.agent_vehicle().fc->status_snapshot().mode, bridge::FcMode::kEmergency);
  EXPECT_EQ(rig.nodes.counters()["fc"]["commands_rejected_source"], kSpoofed);
  double refused = 0.0;
  int events = 0;
  for (const auto& e : r.safety) {
    if (e.kind != "command_refused") continue;
    ++events;
    refused += e.value;
    EXPECT_EQ(e.source, "fc");
    EXPECT_NE(e.detail.find("from CAN node 99"), std::string::npos) << e.detail;
    EXPECT_GT(e.p_W_m[2], 3.0) << "where the vehicle was";
  }
  EXPECT_EQ(refused, kSpoofed);
  EXPECT_GE(events, 10);  // 10 s of attack: one event a second
  EXPECT_LE(events, 12);
}

}  // namespace
}  // namespace a3::rigs
