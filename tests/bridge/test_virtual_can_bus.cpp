// The virtual CAN bus: frames take their wire time (bit stuffing included), the lowest ID
// wins arbitration, a busy bus makes frames wait, load is measured, a bus destroyed with
// events pending cancels them, and DroneCAN nodes talk over it in virtual time.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "bridge/can/frame_timing.hpp"
#include "bridge/can/virtual_can_bus.hpp"
#include "bridge/dronecan/messages.hpp"
#include "bridge/dronecan/node.hpp"
#include "common/virtual_scheduler.hpp"

namespace a3::bridge {
namespace {

CanFrame frame(uint32_t id, uint8_t size, uint8_t fill = 0x55) {
  CanFrame f;
  f.id = id;
  f.size = size;
  f.data.fill(fill);
  return f;
}

TEST(FrameTiming, BitCounts) {
  const CanFrame eight = frame(0x1004062A, 8);
  EXPECT_EQ(can_frame_bits(eight, BitStuffing::kNone), 131u);
  EXPECT_EQ(can_frame_bits(eight, BitStuffing::kWorstCase), 160u);
  const unsigned exact = can_frame_bits(eight, BitStuffing::kExact);
  EXPECT_GE(exact, 131u);
  EXPECT_LE(exact, 160u);

  // A standard frame of 34 zero bits (ID 0, no data, CRC 0): a stuff bit after every 5.
  CanFrame zeros;
  zeros.extended = false;
  zeros.id = 0;
  zeros.size = 0;
  EXPECT_EQ(can_frame_bits(zeros, BitStuffing::kExact), 34u + 6u + 13u);
  EXPECT_EQ(can_frame_bits(zeros, BitStuffing::kWorstCase), 34u + 8u + 13u);

  // 0x55 alternates: the data adds no stuff bits; 0x00 data adds some.
  EXPECT_LT(can_frame_bits(frame(0x1004062A, 8, 0x55)), can_frame_bits(frame(0x1004062A, 8, 0x00)));
}

TEST(FrameTiming, Crc15CheckValue) {
  const uint8_t text[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(can_crc15(text, 72), 0x059E);
}

TEST(FrameTiming, ArbitrationOrder) {
  EXPECT_LT(can_arbitration_key(frame(0x08000010, 8)), can_arbitration_key(frame(0x10000001, 8)));
  CanFrame standard;
  standard.extended = false;
  standard.id = 0x400;
  CanFrame extended = frame(0x400u << 18, 1);
  EXPECT_LT(can_arbitration_key(standard), can_arbitration_key(extended));
  CanFrame remote = frame(0x1000, 0);
  remote.remote = true;
  EXPECT_LT(can_arbitration_key(frame(0x1000, 0)), can_arbitration_key(remote));
}

class VirtualBusTest : public ::testing::Test {
 protected:
  struct Received {
    CanFrame frame;
    int64_t time_us;
  };
  void listen(CanBus& port, std::vector<Received>& into) {
    port.start(scheduler_, [&into](const CanFrame& f, int64_t t) { into.push_back({f, t}); });
  }
  common::VirtualScheduler scheduler_;
};

TEST_F(VirtualBusTest, LowestIdWinsAndFramesTakeTheirWireTime) {
  VirtualCanBus bus(scheduler_, {});
  auto a = bus.attach("a");
  auto b = bus.attach("b");
  auto c = bus.attach("c");
  auto monitor = bus.attach("monitor");
  std::vector<Received> seen, seen_by_a;
  listen(*monitor, seen);
  listen(*a, seen_by_a);
  const CanFrame fa = frame(0x10000003, 8), fb = frame(0x08000002, 8), fc = frame(0x18000001, 8);
  scheduler_.schedule_at(100, [&] {
    ASSERT_TRUE(a->send(fa));
    ASSERT_TRUE(b->send(fb));
    ASSERT_TRUE(c->send(fc));
  });
  scheduler_.run_until(10'000);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].frame, fb);
  EXPECT_EQ(seen[1].frame, fa);
  EXPECT_EQ(seen[2].frame, fc);
  const int64_t tb = bus.frame_time_ns(fb), ta = bus.frame_time_ns(fa), tc = bus.frame_time_ns(fc);
  EXPECT_EQ(seen[0].time_us, 100 + (tb + 999) / 1000);
  EXPECT_EQ(seen[1].time_us, 100 + (tb + ta + 999) / 1000);
  EXPECT_EQ(seen[2].time_us, 100 + (tb + ta + tc + 999) / 1000);
  EXPECT_EQ(seen_by_a.size(), 2u) << "a does not hear its own frame";
  EXPECT_EQ(bus.stats().frames, 3u);
  EXPECT_EQ(bus.stats().busy_ns, ta + tb + tc);
}

TEST_F(VirtualBusTest, ABusyBusMakesAnUrgentFrameWaitButItWinsTheNextArbitration) {
  VirtualCanBus bus(scheduler_, {});
  auto slow = bus.attach("slow");
  auto urgent = bus.attach("urgent");
  auto monitor = bus.attach("monitor");
  std::vector<Received> seen;
  listen(*monitor, seen);
  scheduler_.schedule_at(0, [&] {
    slow->send(frame(0x1F000001, 8, 0x01));
    slow->send(frame(0x1F000001, 8, 0x02));
  });
  scheduler_.schedule_at(10, [&] { urgent->send(frame(0x00000002, 1)); });
  scheduler_.run_until(10'000);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].frame.data[0], 0x01) << "no pre-emption of the frame on the wire";
  EXPECT_EQ(seen[1].frame.id, 0x00000002u) << "then the urgent frame wins";
  EXPECT_EQ(seen[2].frame.data[0], 0x02);
  EXPECT_GT(bus.stats().max_queue_delay_ns, 100'000) << "the second slow frame waited two frames";
}

// One port's own queue is in arbitration order too: a frame with a lower ID queued behind
// others goes before them, frames with equal IDs keep the order sent. And a queue that never
// empties (a port always offering more) keeps that order while it recycles its storage.
TEST_F(VirtualBusTest, APortSendsItsQueueByIdThenInTheOrderSent) {
  VirtualCanBus bus(scheduler_, {});
  auto port = bus.attach("port");
  auto monitor = bus.attach("monitor");
  std::vector<Received> seen;
  listen(*monitor, seen);
  scheduler_.schedule_at(0, [&] {
    port->send(frame(0x1F000001, 8, 1));
    port->send(frame(0x1F000001, 8, 2));
    port->send(frame(0x0A000001, 8, 3));
    port->send(frame(0x1F000001, 8, 4));
    port->send(frame(0x05000001, 8, 5));
    port->send(frame(0x0A000001, 8, 6));
  });
  scheduler_.run_until(10'000);
  std::vector<int> order;
  for (const Received& r : seen) order.push_back(r.frame.data[0]);
  EXPECT_EQ(order, (std::vector<int>{5, 3, 6, 1, 2, 4}));

  seen.clear();
  int sent = 0;
  monitor->start(scheduler_, [&](const CanFrame& f, int64_t t) {
    seen.push_back({f, t});
    // One more for each one heard: three always wait, and the queue never empties.
    if (sent < 300) port->send(frame(0x1F000001, 8, static_cast<uint8_t>(sent++ % 256)));
  });
  scheduler_.schedule_at(20'000, [&] {
    for (int i = 0; i < 4; ++i) port->send(frame(0x1F000001, 8, static_cast<uint8_t>(sent++ % 256)));
  });
  scheduler_.run_until(200'000);
  ASSERT_EQ(seen.size(), 300u);
  for (std::size_t i = 0; i < seen.size(); ++i) {
    ASSERT_EQ(seen[i].frame.data[0], static_cast<uint8_t>(i % 256)) << "frame " << i;
  }
}

// A port that answers from inside its receive handler queues while the bus is idle for an
// instant: the answer's frames still go out one at a time, in order.
TEST_F(VirtualBusTest, FramesQueuedFromAReceiveHandlerKeepTheirOrder) {
  VirtualCanBus bus(scheduler_, {});
  auto asker = bus.attach("asker");
  auto answerer = bus.attach("answerer");
  auto monitor = bus.attach("monitor");
  std::vector<Received> seen;
  listen(*monitor, seen);
  asker->start(scheduler_, [](const CanFrame&, int64_t) {});
  answerer->start(scheduler_, [&](const CanFrame&, int64_t) {
    answerer->send(frame(0x10000005, 8, 0x01));
    answerer->send(frame(0x10000005, 1, 0x02));
  });
  scheduler_.schedule_at(0, [&] { asker->send(frame(0x10000004, 8)); });
  scheduler_.run_until(10'000);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[1].frame.data[0], 0x01);
  EXPECT_EQ(seen[2].frame.data[0], 0x02);
  EXPECT_GE(seen[2].time_us - seen[1].time_us, bus.frame_time_ns(seen[2].frame) / 1000)
      << "the second frame waited for the first to leave the wire";
  EXPECT_EQ(bus.stats().busy_ns, bus.frame_time_ns(seen[0].frame) + bus.frame_time_ns(seen[1].frame) +
                                     bus.frame_time_ns(seen[2].frame));
}

TEST_F(VirtualBusTest, BusLoadFollowsTheOfferedTraffic) {
  for (double bit_rate : {1e6, 250e3}) {
    common::VirtualScheduler scheduler;
    VirtualCanBusConfig config;
    config.bit_rate_bps = bit_rate;
    VirtualCanBus bus(scheduler, config);
    auto sender = bus.attach("sender");
    const CanFrame f = frame(0x10000001, 8);
    const double frame_s = bus.frame_time_ns(f) * 1e-9;
    // 1000 frames/s for one second.
    scheduler.schedule(0, 1000, [&] { sender->send(f); });
    scheduler.run_until(1'000'000);
    EXPECT_NEAR(bus.stats().load(1'000'000), 1000 * frame_s, 0.01) << bit_rate;
  }
}

TEST_F(VirtualBusTest, AnOverloadedBusQueuesThenRefuses) {
  VirtualCanBusConfig config;
  config.tx_queue_frames = 16;
  VirtualCanBus bus(scheduler_, config);
  auto sender = bus.attach("sender");
  int refused = 0;
  // 20,000 frames/s of ~130 µs frames: twice what 1 Mbit/s carries.
  scheduler_.schedule(0, 50, [&] {
    if (!sender->send(frame(0x10000001, 8))) ++refused;
  });
  scheduler_.run_until(200'000);
  EXPECT_GT(refused, 1000);
  EXPECT_EQ(sender->stats().send_refused, static_cast<uint64_t>(refused));
  EXPECT_EQ(sender->stats().tx_queue_peak, 16u);
  EXPECT_GT(bus.stats().load(200'000), 0.98);
}

// The bus's events hold only a pointer to it: going away with a frame on the wire and an
// arbitration pending, it cancels both; its ports then refuse frames.
TEST_F(VirtualBusTest, ABusDestroyedWithAFrameOnTheWireCancelsItsEvents) {
  std::vector<Received> seen;
  std::unique_ptr<CanBus> sender, listener;
  {
    VirtualCanBus bus(scheduler_, {});
    sender = bus.attach("sender");
    listener = bus.attach("listener");
    listen(*listener, seen);
    sender->send(frame(0x10000001, 8));
    scheduler_.run_until(0);  // the arbitration: the frame is on the wire until ~130 us
    scheduler_.schedule_at(50, [&] { sender->send(frame(0x10000002, 8)); });
    scheduler_.run_until(50);  // queued behind it
    ASSERT_EQ(scheduler_.pending(), 1u) << "the end of the frame on the wire";
    listener->send(frame(0x08000001, 1));  // and a frame of another port
  }
  EXPECT_EQ(scheduler_.pending(), 0u);
  scheduler_.run_until(10'000);
  EXPECT_TRUE(seen.empty());
  EXPECT_FALSE(sender->send(frame(0x10000003, 8)));
  EXPECT_EQ(sender->stats().send_refused, 1u);
}

TEST_F(VirtualBusTest, APortDestroyedBeforeTheBusLeavesIt) {
  std::vector<Received> seen;
  {
    VirtualCanBus bus(scheduler_, {});
    auto sender = bus.attach("sender");
    auto gone = bus.attach("gone");
    auto listener = bus.attach("listener");
    std::vector<Received> never;
    listen(*gone, never);
    listen(*listener, seen);
    gone.reset();
    EXPECT_TRUE(sender->send(frame(0x10000001, 8)));
    scheduler_.run_until(1'000);
    EXPECT_EQ(seen.size(), 1u);
    EXPECT_TRUE(never.empty());
    sender.reset();  // the bus goes last, with one port left
  }
  EXPECT_EQ(scheduler_.pending(), 0u);
}

TEST_F(VirtualBusTest, DroneCanNodesExchangeMultiFrameTransfersInVirtualTime) {
  VirtualCanBus bus(scheduler_, {});
  auto imu_port = bus.attach("imu");
  auto fc_port = bus.attach("fc");
  DroneCanNodeConfig imu_config;
  imu_config.node_id = 10;
  DroneCanNodeConfig fc_config;
  fc_config.node_id = 20;
  DroneCanNode imu(*imu_port, imu_config);
  DroneCanNode fc(*fc_port, fc_config);
  std::vector<AhrsRawImu> received;
  std::vector<int64_t> times;
  fc.subscribe<AhrsRawImu>([&](const AhrsRawImu& m, const ReceivedTransfer& t) {
    received.push_back(m);
    times.push_back(scheduler_.clock().now_us());
    EXPECT_EQ(t.header.source_node_id, 10);
  });
  std::vector<NodeStatus> statuses;
  fc.subscribe<NodeStatus>([&](const NodeStatus& m, const ReceivedTransfer&) { statuses.push_back(m); });
  imu.publish_node_status_every(1'000'000);
  imu.start(scheduler_);
  fc.start(scheduler_);
  // 200 Hz IMU for 2 s.
  int sequence = 0;
  scheduler_.schedule(5000, 5000, [&] {
    AhrsRawImu m;
    m.timestamp.usec = static_cast<uint64_t>(scheduler_.clock().now_us());
    m.integration_interval = static_cast<float>(++sequence);
    m.covariance = {1, 2, 3, 4, 5, 6};
    imu.publish(m, kPriorityHigh);
  });
  scheduler_.run_until(2'000'000);
  ASSERT_EQ(received.size(), 399u);
  for (std::size_t i = 0; i < received.size(); ++i) {
    EXPECT_EQ(received[i].integration_interval, static_cast<float>(i + 1));
    // A 59-byte RawIMU is 9 frames: about 1.1 ms on the wire at 1 Mbit/s.
    const int64_t latency = times[i] - static_cast<int64_t>(received[i].timestamp.usec);
    EXPECT_GT(latency, 900);
    EXPECT_LT(latency, 1400);
  }
  ASSERT_EQ(statuses.size(), 2u) << "NodeStatus at 0 and 1 s (the one at 2 s is still on the wire)";
  EXPECT_EQ(statuses.back().uptime_sec, 1u);
  EXPECT_EQ(fc.reassembler_stats().rejected_frames(), 0u);
  EXPECT_EQ(fc.stats().transfers_received, 401u);
  // 200 Hz x 9 frames x ~140 bits (8 data bytes, stuffing, intermission) = 0.25 of 1 Mbit/s.
  EXPECT_NEAR(bus.stats().load(2'000'000), 0.25, 0.015);
}

}  // namespace
}  // namespace a3::bridge
