// A thread-safe sink of outgoing MCP messages for the protocol tests, with a bounded wait.
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <vector>

namespace a3::agent::mcp::testing {

class MessageSink {
 public:
  void operator()(const nlohmann::json& message) {
    {
      std::lock_guard lock(mutex_);
      messages_.push_back(message);
    }
    cv_.notify_all();
  }
  // Every message so far, once there are at least `count` (or what there is after 10 s).
  std::vector<nlohmann::json> wait_for(size_t count) {
    std::unique_lock lock(mutex_);
    cv_.wait_for(lock, std::chrono::seconds(10), [&] { return messages_.size() >= count; });
    return messages_;
  }
  std::vector<nlohmann::json> all() {
    std::lock_guard lock(mutex_);
    return messages_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<nlohmann::json> messages_;
};

}  // namespace a3::agent::mcp::testing
