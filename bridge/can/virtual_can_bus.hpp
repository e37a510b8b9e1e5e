// A simulated CAN bus for the virtual-time runtime (or any Executor): nodes attach ports
// (each a CanBus); a frame wins the bus by arbitration (lowest arbitration key, i.e. lowest
// CAN ID, among the frames waiting at every port) and is delivered to every other started
// port when its last bit has crossed the wire, bits / bit rate later (bit stuffing exact by
// default, see frame_timing.hpp). Frames sent at the same instant compete in one arbitration;
// a frame queued while the bus is busy waits for the end of the current frame. Each port
// queues its frames in arbitration order (FIFO for equal IDs), as a CAN controller with
// priority-ordered transmit buffers does. Bus load, queueing delay and per-port queue
// depth are measured. Single-threaded, like the executor it runs on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "bridge/can/can_bus.hpp"
#include "bridge/can/frame_timing.hpp"
#include "common/executor.hpp"

namespace a3::bridge {

struct VirtualCanBusConfig {
  double bit_rate_bps = 1'000'000;       // classic CAN: 10 kbit/s .. 1 Mbit/s
  BitStuffing stuffing = BitStuffing::kExact;
  std::size_t tx_queue_frames = 256;     // per port; send() beyond it is refused
};

struct VirtualCanBusStats {
  uint64_t frames = 0;             // frames that crossed the wire
  uint64_t bits = 0;               // their bits, stuffing and intermission included
  int64_t busy_ns = 0;             // time the wire was busy
  int64_t max_queue_delay_ns = 0;  // longest wait from send() to the start of transmission
  int64_t total_queue_delay_ns = 0;
  int64_t first_frame_start_ns = -1;  // -1: no frame yet
  // Busy fraction of the time from the first frame's start to now_us (0..1).
  double load(int64_t now_us) const;
};

class VirtualCanBus {
 public:
  // The executor runs the bus's events; it must outlive the bus and its ports.
  VirtualCanBus(common::Executor& executor, VirtualCanBusConfig config = {});
  ~VirtualCanBus();
  VirtualCanBus(const VirtualCanBus&) = delete;
  VirtualCanBus& operator=(const VirtualCanBus&) = delete;

  // A new node's connection to the bus. Ports may outlive the bus (they then refuse sends).
  std::unique_ptr<CanBus> attach(const std::string& port_name);

  const VirtualCanBusConfig& config() const;
  VirtualCanBusStats stats() const;
  // Time one frame occupies the wire at this bus's bit rate and stuffing, in nanoseconds.
  int64_t frame_time_ns(const CanFrame& frame) const;

  struct Impl;

 private:
  std::shared_ptr<Impl> impl_;
};

}  // namespace a3::bridge
