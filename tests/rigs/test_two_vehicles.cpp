// Two vehicles in one virtual-time rig (issue 33), no agent: each is a dynamics node driven by an
// actuator script, with a bridge turning its state into sensor frames on a CAN bus of its own.
// Vehicle 0 hovers at 20 m, vehicle 1 at 60 m; their channels (A3_STATE, A3_V1_STATE), states
// and CAN buses do not mix: each bridge hears only its vehicle, and each bus carries the static
// pressure of its own vehicle's altitude.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "bridge/can/virtual_can_bus.hpp"
#include "bridge/dronecan/msg/air_data.hpp"
#include "bridge/dronecan/node.hpp"
#include "bridge/sim/bridge_node.hpp"
#include "common/channels.hpp"
#include "common/runtime.hpp"
#include "dynamics/actuator_script_node.hpp"
#include "dynamics/dynamics_node.hpp"
#include "dynamics/quadrotor_model.hpp"

namespace a3 {
namespace {

namespace ch = common::channels;

// One vehicle: physics, its scripted rotors, its bridge on its own CAN bus, and a listener there.
struct TestVehicle {
  TestVehicle(common::VirtualRuntime& rt, common::VehicleId id, double z_m) : can(rt.scheduler()) {
    dynamics::DynamicsNodeConfig d;
    const dynamics::QuadrotorModel model(d.params);
    d.initial_state.p_W_m = {10.0 * id, 0, z_m};
    d.initial_state.rotor_speed_radps.fill(model.hover_speed_radps());
    d.vehicle = id;
    d.seed = 1 + id;
    const double h = model.hover_throttle();
    dynamics::ActuatorScript s;
    s.throttle = [h](double) { return std::array<double, 4>{h, h, h, h}; };
    s.vehicle = id;
    bridge::BridgeNodeConfig b;
    b.vehicle = id;
    bridge_port = can.attach("bridge");
    listener_port = can.attach("listener");
    physics = std::make_unique<dynamics::DynamicsNode>(d);
    rotors = std::make_unique<dynamics::ActuatorScriptNode>(s);
    sensors = std::make_unique<bridge::BridgeNode>(*bridge_port, b);
    listener = std::make_unique<bridge::DroneCanNode>(*listener_port, bridge::DroneCanNodeConfig{127, {}, 500'000});
    listener->subscribe<bridge::StaticPressure>(
        [this](const bridge::StaticPressure& m, const bridge::ReceivedTransfer&) { pressures_Pa.push_back(m.static_pressure); });
    rt.add(*physics);
    rt.add(*rotors);
    rt.add(*sensors);
    listener->start(rt.scheduler());
    rt.bus().subscribe(ch::kState.of(id), [this](const a3lcm::vehicle_state_t& m, int64_t) { states.push_back(m); });
  }

  bridge::VirtualCanBus can;
  std::unique_ptr<bridge::CanBus> bridge_port, listener_port;
  std::unique_ptr<dynamics::DynamicsNode> physics;
  std::unique_ptr<dynamics::ActuatorScriptNode> rotors;
  std::unique_ptr<bridge::BridgeNode> sensors;
  std::unique_ptr<bridge::DroneCanNode> listener;
  std::vector<a3lcm::vehicle_state_t> states;
  std::vector<float> pressures_Pa;
};

TEST(TwoVehicles, ChannelsStatesAndCanBusesDoNotMix) {
  common::VirtualRuntime rt;
  TestVehicle low(rt, 0, 20.0), high(rt, 1, 60.0);
  rt.run_until(5'000'000);

  // Each state channel carries its own vehicle, at its own rate, at its own altitude.
  ASSERT_GT(low.states.size(), 400u);
  EXPECT_EQ(low.states.size(), high.states.size());
  for (const auto& s : low.states) EXPECT_NEAR(s.p_W_m[2], 20.0, 1.0);
  for (const auto& s : high.states) EXPECT_NEAR(s.p_W_m[2], 60.0, 1.0);
  EXPECT_NEAR(high.states.back().p_W_m[0], 10.0, 0.5);

  // Each bridge took its own vehicle's states only (a mixed channel would double them or reject
  // the other's as out of order).
  const auto states_of = [](const bridge::BridgeNode& b) { return b.counters().get("states"); };
  EXPECT_EQ(states_of(*low.sensors), low.states.size());
  EXPECT_EQ(states_of(*high.sensors), high.states.size());
  EXPECT_EQ(low.sensors->counters().get("states_rejected"), 0u);
  EXPECT_EQ(high.sensors->counters().get("states_rejected"), 0u);

  // Each CAN bus carries its own vehicle's air pressure: 40 m apart is about 470 Pa near sea level.
  ASSERT_GT(low.pressures_Pa.size(), 10u);
  ASSERT_GT(high.pressures_Pa.size(), 10u);
  const float low_max = *std::max_element(low.pressures_Pa.begin(), low.pressures_Pa.end());
  const float low_min = *std::min_element(low.pressures_Pa.begin(), low.pressures_Pa.end());
  const float high_max = *std::max_element(high.pressures_Pa.begin(), high.pressures_Pa.end());
  EXPECT_GT(low_min - high_max, 300.0f) << "bus 0: " << low_min << ".." << low_max << " Pa, bus 1 up to " << high_max;
}

}  // namespace
}  // namespace a3
