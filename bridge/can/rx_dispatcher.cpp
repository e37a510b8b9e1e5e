// I/O thread -> executor hand-off of received frames (see rx_dispatcher.hpp).
#include "bridge/can/rx_dispatcher.hpp"

namespace a3::bridge {

void RxDispatcher::start(common::Executor& executor, CanFrameHandler handler) {
  std::lock_guard lock(mutex_);
  executor_ = &executor;
  handler_ = std::make_shared<CanFrameHandler>(std::move(handler));
  active_ = std::make_shared<std::atomic<bool>>(true);
}

void RxDispatcher::stop() {
  std::lock_guard lock(mutex_);
  executor_ = nullptr;
  handler_.reset();
  if (active_) active_->store(false);
  active_.reset();
}

bool RxDispatcher::started() const {
  std::lock_guard lock(mutex_);
  return executor_ != nullptr;
}

int64_t RxDispatcher::now_us() const {
  std::lock_guard lock(mutex_);
  return executor_ != nullptr ? executor_->clock().now_us() : 0;
}

std::size_t RxDispatcher::flush() {
  if (batch_.empty()) return 0;
  std::lock_guard lock(mutex_);
  if (executor_ == nullptr) {
    batch_.clear();
    return 0;
  }
  const std::size_t count = batch_.size();
  executor_->schedule(executor_->clock().now_us(), 0,
                      [handler = handler_, active = active_, batch = std::move(batch_)] {
                        for (const auto& [frame, rx_time_us] : batch) {
                          if (!active->load()) return;
                          (*handler)(frame, rx_time_us);
                        }
                      });
  batch_ = {};
  return count;
}

}  // namespace a3::bridge
