// The virtual CAN bus allocates nothing per frame once warmed up: queueing at several ports
// (frames waiting behind a busy wire), arbitration, wire time and delivery to the listening
// ports. Counted by replacing operator new in this test program (tests/common's counter).
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>

#include "bridge/can/virtual_can_bus.hpp"
#include "common/virtual_scheduler.hpp"
#include "tests/common/counting_operator_new.hpp"

namespace a3::bridge {
namespace {

CanFrame frame(uint32_t id, uint8_t size, uint8_t fill) {
  CanFrame f;
  f.id = id;
  f.size = size;
  f.data.fill(fill);
  return f;
}

// Every 4 ms (about half the wire at 1 Mbit/s): a burst of 8 frames from one port, 4 from
// another (queued behind the first when they meet), and that one's answer to the 8th frame
// from its receive handler; a third port listens to all of them.
struct Traffic {
  explicit Traffic(common::VirtualScheduler& scheduler)
      : bus(scheduler, {}), imu(bus.attach("imu")), fc(bus.attach("fc")), monitor(bus.attach("monitor")) {
    monitor->start(scheduler, [this](const CanFrame&, int64_t) { ++heard; });
    fc->start(scheduler, [this](const CanFrame& f, int64_t) {
      if (f.data[0] == 7) fc->send(frame(0x10000020, 4, 0x11));
    });
    scheduler.schedule_every(4000, [this] {
      for (uint8_t i = 0; i < 8; ++i) imu->send(frame(0x10000010 + (i % 3), 8, i));
    });
    scheduler.schedule(2000, 4000, [this] {
      for (uint8_t i = 0; i < 4; ++i) fc->send(frame(0x0C000001, 8, static_cast<uint8_t>(0x80 | i)));
    });
  }
  VirtualCanBus bus;
  std::unique_ptr<CanBus> imu, fc, monitor;
  uint64_t heard = 0;
};

TEST(CanBusAllocations, FramesOnTheVirtualBusAllocateNothingAfterWarmUp) {
  common::VirtualScheduler scheduler;
  Traffic traffic(scheduler);
  scheduler.run_until(99'000);  // the wire is idle here, and 1 s later
  const uint64_t frames_before = traffic.bus.stats().frames, heard_before = traffic.heard;
  test::start_counting_allocations();
  scheduler.run_until(1'099'000);
  EXPECT_EQ(test::allocations_counted(), 0);
  EXPECT_EQ(traffic.bus.stats().frames - frames_before, 250u * 13u);
  EXPECT_EQ(traffic.heard - heard_before, 250u * 13u);
  EXPECT_EQ(traffic.imu->stats().send_refused + traffic.fc->stats().send_refused, 0u);
}

}  // namespace
}  // namespace a3::bridge
