// A watcher thread that asks a question every so often and stops at once when it goes.
// poll() runs on the thread every period until it returns true; the destructor wakes the thread
// (it does not wait out the rest of a period, so a short program does not end up to one period
// late) and joins it. For flags a signal handler or another thread sets, where a plain wait
// on a condition is not possible.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace a3::common {

class PollThread {
 public:
  PollThread(std::chrono::milliseconds period, std::function<bool()> poll)
      : thread_([this, period, poll = std::move(poll)] {
          std::unique_lock<std::mutex> lock(mutex_);
          while (!finished_) {
            lock.unlock();
            if (poll()) return;
            lock.lock();
            wake_.wait_for(lock, period, [this] { return finished_; });
          }
        }) {}
  ~PollThread() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      finished_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  PollThread(const PollThread&) = delete;
  PollThread& operator=(const PollThread&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool finished_ = false;
  std::thread thread_;  // last: starts once the members above exist
};

}  // namespace a3::common
