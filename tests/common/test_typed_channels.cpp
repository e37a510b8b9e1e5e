// Typed, vehicle-scoped channels and declared ports (issue 33): vehicle 0 keeps the plain names,
// vehicle n gets A3_V<n>_..., a typed publish reaches a typed subscriber on the same channel only,
// and a node that publishes or subscribes outside its declared ports is stopped at once.
#include <gtest/gtest.h>

#include <set>

#include "common/channels.hpp"
#include "common/port_checked_bus.hpp"
#include "common/runtime.hpp"

namespace a3::common {
namespace {

namespace ch = channels;

TEST(TypedChannels, VehicleZeroKeepsThePlainNamesAndOthersAreTagged) {
  EXPECT_EQ(ch::kState.of(0).name, "A3_STATE");
  EXPECT_EQ(ch::kState.of(1).name, "A3_V1_STATE");
  EXPECT_EQ(ch::kLinkDownRx.of(12).name, "A3_V12_LINK_DOWN_RX");
  EXPECT_EQ(std::string(ch::kClock.name), "A3_CLOCK");
  // The declared list has every channel once per vehicle and the rig's once.
  const auto v1 = ch::declared_channels(1);
  std::set<std::string> names;
  for (const auto& c : v1) names.insert(c.name);
  EXPECT_EQ(names.size(), v1.size());
  EXPECT_TRUE(names.count("A3_V1_FC_CMD"));
  EXPECT_TRUE(names.count("A3_TRAFFIC"));
  EXPECT_FALSE(names.count("A3_STATE"));
}

// Publishes one state on vehicle `vehicle`'s channel, declared or not.
class StatePublisher final : public Node {
 public:
  StatePublisher(VehicleId declared, VehicleId used) : declared_(declared), used_(used) {}
  std::string name() const override { return "state_publisher"; }
  void start(Executor& executor, Bus& bus) override {
    executor.schedule_at(1000, [this, &bus] {
      a3lcm::vehicle_state_t s{};
      s.utime_us = 1000;
      bus.publish(ch::kState.of(used_), s);
    });
  }
  std::optional<NodePorts> ports() const override { return NodePorts().publishes(ch::kState.of(declared_)); }

 private:
  VehicleId declared_, used_;
};

TEST(TypedChannels, EachVehiclesSubscriberHearsOnlyItsOwnVehicle) {
  VirtualRuntime rt;
  StatePublisher zero(0, 0), one(1, 1);
  int heard0 = 0, heard1 = 0;
  rt.bus().subscribe(ch::kState.of(0), [&](const a3lcm::vehicle_state_t&, int64_t) { ++heard0; });
  rt.bus().subscribe(ch::kState.of(1), [&](const a3lcm::vehicle_state_t&, int64_t) { ++heard1; });
  rt.add(zero);
  rt.add(one);
  rt.run_until(5000);
  EXPECT_EQ(heard0, 1);
  EXPECT_EQ(heard1, 1);
}

TEST(TypedChannels, ANodePublishingOutsideItsPortsIsStopped) {
  VirtualRuntime rt;
  StatePublisher stray(0, 1);  // declares vehicle 0, publishes vehicle 1's state
  rt.add(stray);
  try {
    rt.run_until(5000);
    FAIL() << "an undeclared publication went through";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("node state_publisher published on A3_V1_STATE"), std::string::npos) << e.what();
  }
}

TEST(TypedChannels, ASubscriptionOutsideThePortsIsRefused) {
  VirtualScheduler scheduler;
  VirtualBus bus(scheduler);
  PortCheckedBus checked(bus, "listener", NodePorts().subscribes(ch::kState.of(0)));
  EXPECT_NO_THROW(checked.subscribe(ch::kState.of(0), [](const a3lcm::vehicle_state_t&, int64_t) {}));
  EXPECT_THROW(checked.subscribe(ch::kFcStatus.of(0), [](const a3lcm::fc_status_t&, int64_t) {}), std::logic_error);
}

}  // namespace
}  // namespace a3::common
