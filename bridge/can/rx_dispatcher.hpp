// Hands frames read by a transport's I/O thread to the node's executor: the I/O thread
// stamps and collects them, then posts one task per batch, so the handler runs on the
// executor's thread like every other callback of the node.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "bridge/can/can_bus.hpp"
#include "common/executor.hpp"

namespace a3::bridge {

class RxDispatcher {
 public:
  void start(common::Executor& executor, CanFrameHandler handler);
  void stop();
  bool started() const;
  // I/O thread: the executor clock's time now (the frames' receive time).
  int64_t now_us() const;
  // I/O thread: collects one frame, then flush() posts what was collected.
  void push(const CanFrame& frame, int64_t rx_time_us) { batch_.emplace_back(frame, rx_time_us); }
  // Returns how many frames were posted (0 when stopped: they are discarded).
  std::size_t flush();

 private:
  mutable std::mutex mutex_;
  common::Executor* executor_ = nullptr;
  std::shared_ptr<CanFrameHandler> handler_;
  // Cleared by stop(): batches posted earlier but not yet run are then dropped too.
  std::shared_ptr<std::atomic<bool>> active_;
  std::vector<std::pair<CanFrame, int64_t>> batch_;
};

}  // namespace a3::bridge
