// The CanBus interface: how a node puts classic CAN frames on a bus and gets the frames
// other nodes put there. Implementations: SocketCanBus (a Linux CAN interface: vcan0, can0),
// UserspaceCanBus (processes on one machine, for kernels without CAN), VirtualCanBus ports
// (the virtual-time runtime, with arbitration and wire time). A node never receives its own
// frames, as on SocketCAN by default.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "bridge/can/can_frame.hpp"
#include "common/executor.hpp"

namespace a3::bridge {

// Called on the executor given to start(), one frame at a time, in arrival order.
// rx_time_us is the executor clock's time when the frame arrived.
using CanFrameHandler = std::function<void(const CanFrame& frame, int64_t rx_time_us)>;

struct CanBusStats {
  uint64_t frames_sent = 0;      // accepted by send() (on the wire or queued for it)
  uint64_t frames_received = 0;  // passed to the handler
  uint64_t send_refused = 0;     // send() returned false: transmit queue full, bus gone
  uint64_t receive_errors = 0;   // malformed frames from the transport, dropped
  uint64_t peer_overruns = 0;    // userspace bus: frames a slow peer could not take
  uint64_t receive_overruns = 0;  // SocketCAN: frames the kernel dropped, read too slowly
  std::size_t tx_queue_peak = 0;  // most frames waiting to be sent at once
};

class CanBus {
 public:
  virtual ~CanBus() = default;

  // "socketcan:vcan0", "userspace:vcan0", "virtual:fc", ...
  virtual std::string name() const = 0;
  // Queues one frame for the bus; never blocks. False when refused (counted in stats()).
  // Thread-safe for the real-time transports.
  virtual bool send(const CanFrame& frame) = 0;
  // Starts delivering received frames to handler on executor. The executor must be the one
  // the node runs on (a RealTimeExecutor for the real transports, the VirtualScheduler for
  // virtual ports) and outlive the bus, or stop() must be called first.
  virtual void start(common::Executor& executor, CanFrameHandler handler) = 0;
  // Stops delivering; frames that arrive afterwards are discarded. Idempotent.
  virtual void stop() = 0;
  // Frames accepted by send() that are not on the bus yet.
  virtual std::size_t tx_pending() const = 0;
  virtual CanBusStats stats() const = 0;
};

}  // namespace a3::bridge
