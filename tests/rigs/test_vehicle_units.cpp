// A vehicle is one unit the rig builds N times (rigs/run/vehicle_unit.hpp): two units from the
// same scenario, vehicles 0 and 1, each with its dynamics, bridge and fc on a CAN bus of its own,
// in one virtual-time rig with no agent. Vehicle 1 is told to take off over its own channels;
// vehicle 0 is told nothing and stays on the ground: commands, states, fc statuses and CAN
// frames do not cross from one unit to the other.
#include <gtest/gtest.h>

#include <memory>

#include "bridge/can/virtual_can_bus.hpp"
#include "common/runtime.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/run/node_configs.hpp"
#include "rigs/run/vehicle_unit.hpp"
#include "tests/bridge_nodes/closed_loop.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

using Cmd = a3lcm::fc_command_t;

struct Unit {
  Unit(common::VirtualRuntime& rt, const Scenario& s, const RunOptions& o, common::VehicleId id)
      : configs(make_vehicle_configs(s, o, id)), can(rt.scheduler()), ground(id) {
    configs.dynamics.initial_state.p_W_m.x() += 30.0 * id;  // side by side on the pad
    can_bridge = can.attach("bridge");
    can_fc = can.attach("fc");
    nodes = make_vehicle({RigPart::kDynamics, RigPart::kBridge, RigPart::kFc}, configs, {can_bridge.get(), can_fc.get()});
    rt.add(ground);
    for (common::Node* n : nodes.in_start_order()) rt.add(*n);
  }

  VehicleConfigs configs;
  bridge::VirtualCanBus can;
  std::unique_ptr<bridge::CanBus> can_bridge, can_fc;
  VehicleNodes nodes;
  test::GroundStation ground;
};

TEST(VehicleUnits, TwoUnitsFromOneScenarioFlyApart) {
  const RunOptions o = test::virtual_run("parcel-delivery", "vehicle-units");
  const Scenario s = load_scenario_spec(o.scenario, o.shared_dir);
  common::VirtualRuntime rt;
  Unit first(rt, s, o, 0), second(rt, s, o, 1);
  EXPECT_EQ(second.configs.tool_server.vehicle, 1);
  EXPECT_EQ(second.configs.link.channels.up_rx, common::channels::kLinkUpRx.of(1).name);

  rt.run_until(2'000'000);
  second.ground.command(Cmd::TAKEOFF, second.ground.state.p_W_m[0], second.ground.state.p_W_m[1], 15.0);
  rt.run_until(25'000'000);

  ASSERT_GT(first.ground.states, 1000u);
  EXPECT_EQ(first.ground.states, second.ground.states) << "each state channel carries its own vehicle";
  EXPECT_NEAR(second.ground.state.p_W_m[2], 15.0, 1.5) << "vehicle 1 took off";
  EXPECT_LT(first.ground.state.p_W_m[2], 0.2) << "vehicle 0 was told nothing and stayed down";
  EXPECT_NEAR(second.ground.state.p_W_m[0] - first.ground.state.p_W_m[0], 30.0, 1.0);
  ASSERT_FALSE(first.ground.statuses.empty());
  ASSERT_FALSE(second.ground.statuses.empty());
  // Heartbeats reach both fcs from their own ground stations; the take-off only vehicle 1's.
  const auto non_heartbeats = [](const bridge::FcNode& fc) {
    return fc.counters().get("commands") - fc.counters().get("heartbeats");
  };
  EXPECT_GT(first.nodes.fc->counters().get("heartbeats"), 50u);
  EXPECT_EQ(non_heartbeats(*first.nodes.fc), 0u) << "vehicle 1's command reached vehicle 0's fc";
  EXPECT_EQ(non_heartbeats(*second.nodes.fc), 1u);
  EXPECT_EQ(first.nodes.bridge->counters().get("states_rejected"), 0u);
  EXPECT_EQ(second.nodes.bridge->counters().get("states_rejected"), 0u);
}

}  // namespace
}  // namespace a3::rigs
