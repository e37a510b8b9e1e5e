// `a3rig topology` (issue 33): every built-in scenario's rig, in each runtime, is a whole graph —
// every node declares its ports, every subscription has a publisher, one type per channel — so a
// node that starts listening to a channel nobody publishes fails here; and a broken graph is
// named as such.
#include <gtest/gtest.h>

#include "common/channels.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/run/rig_topology.hpp"
#include "rigs/scenario/builtin_scenarios.hpp"
#include "rigs/scenario/scenario.hpp"
#include "tests/test_support.hpp"

namespace a3::rigs {
namespace {

namespace ch = common::channels;

RigTopology topology_of(const std::string& scenario_name, Runtime runtime, Sync sync) {
  RunOptions o;
  o.runtime = runtime;
  o.sync = sync;
  return rig_topology(load_scenario_spec(scenario_name, test::shared_dir()), o);
}

TEST(Topology, EveryBuiltInRigIsAWholeGraphInEachRuntime) {
  for (const auto& [scenario, text] : builtin_scenarios()) {
    const std::string name(scenario);
    for (const auto& [runtime, sync] : {std::pair{Runtime::kVirtual, Sync::kLockstep}, {Runtime::kReal, Sync::kLockstep},
                                        {Runtime::kReal, Sync::kFree}}) {
      const RigTopology t = topology_of(name, runtime, sync);
      const auto problems = topology_problems(t);
      std::string listed;
      for (const auto& p : problems) listed += p + "\n";
      EXPECT_TRUE(problems.empty()) << name << ":\n" << listed << topology_text(t);
    }
  }
}

TEST(Topology, TheTextNamesEachChannelsTypePublishersAndSubscribers) {
  const std::string text = topology_text(topology_of("traffic-conflict", Runtime::kReal, Sync::kLockstep));
  EXPECT_NE(text.find("A3_STATE  a3lcm.vehicle_state_t\n    published by  dynamics\n"), std::string::npos) << text;
  EXPECT_NE(text.find("A3_CLOCK  a3lcm.sim_clock_t\n    published by  (lockstep pacer)"), std::string::npos) << text;
  const std::string dot = topology_dot(topology_of("traffic-conflict", Runtime::kVirtual, Sync::kLockstep));
  EXPECT_EQ(dot.rfind("digraph a3rig {", 0), 0u);
  EXPECT_NE(dot.find("\"dynamics\" -> \"A3_STATE\";"), std::string::npos) << dot;
  EXPECT_NE(dot.find("\"A3_EDGE_REQ\" -> \"linkemu\" [style=dashed];"), std::string::npos) << dot;
}

TEST(Topology, ASubscriptionNobodyPublishesAndAMixedTypeAreProblems) {
  RigTopology t;
  t.nodes.push_back({"listener", common::NodePorts().subscribes(ch::kFcStatus.of(1))});
  t.nodes.push_back({"a", common::NodePorts().publishes(common::TypedChannel<a3lcm::vehicle_state_t>{"X"})});
  t.nodes.push_back({"b", common::NodePorts().publishes(common::TypedChannel<a3lcm::fc_status_t>{"X"})});
  t.nodes.push_back({"edge", common::NodePorts().listens(ch::kEdgeRequest.of(0))});
  const auto problems = topology_problems(t);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0], "A3_V1_FC_STATUS: listener subscribes but no node publishes it");
  EXPECT_EQ(problems[1].rfind("X: carries more than one message type", 0), 0u) << problems[1];
}

}  // namespace
}  // namespace a3::rigs
