// CanBus on a Linux SocketCAN interface (vcan0, can0, ...) through a raw CAN socket.
// Sends go straight to the socket; when the interface's queue is full (EAGAIN/ENOBUFS) they
// wait in a bounded queue that the I/O thread drains. The I/O thread (running from
// construction to destruction) also reads frames and, once start() names an executor, hands
// them to it (real-time runtime only); frames that arrive before start() are dropped.
#pragma once

#include <atomic>
#include <cstddef>
#include <deque>
#include <mutex>
#include <string>
#include <thread>

#include "bridge/can/can_bus.hpp"
#include "bridge/can/rx_dispatcher.hpp"

namespace a3::bridge {

struct SocketCanOptions {
  std::size_t tx_queue_frames = 1024;  // frames waiting for the interface; beyond: refused
  bool receive_own_frames = false;     // CAN_RAW_RECV_OWN_MSGS
  // Kernel receive buffer: the default (~200 KiB) holds only ~300 frames, too few for
  // bursts when the reader is slow (e.g. under emulation). Needs root beyond rmem_max.
  int receive_buffer_bytes = 8 << 20;
};

class SocketCanBus final : public CanBus {
 public:
  // Opens and binds a raw CAN socket. Throws std::runtime_error saying why it cannot (no
  // SocketCAN in this kernel, no such interface, not a CAN interface, interface down).
  explicit SocketCanBus(const std::string& interface, SocketCanOptions options = {});
  ~SocketCanBus() override;
  SocketCanBus(const SocketCanBus&) = delete;
  SocketCanBus& operator=(const SocketCanBus&) = delete;

  // "" when `interface` can be opened as SocketCAN here, else the reason it cannot.
  static std::string probe(const std::string& interface);

  std::string name() const override { return "socketcan:" + interface_; }
  bool send(const CanFrame& frame) override;
  void start(common::Executor& executor, CanFrameHandler handler) override;
  void stop() override;
  std::size_t tx_pending() const override;
  CanBusStats stats() const override;

 private:
  void run();
  void stop_io_thread();
  void wake();
  // Writes queued frames until the socket would block; returns the errno that stopped it.
  int drain_locked();
  // One write; 0 on success, else errno.
  int write_frame(const CanFrame& frame);

  std::string interface_;
  SocketCanOptions options_;
  int socket_fd_ = -1;
  int wake_fd_ = -1;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  RxDispatcher dispatcher_;
  mutable std::mutex mutex_;  // tx queue and stats
  std::deque<CanFrame> tx_queue_;
  CanBusStats stats_;
  uint32_t kernel_drops_ = 0;  // SO_RXQ_OVFL: cumulative count from the kernel
};

}  // namespace a3::bridge
