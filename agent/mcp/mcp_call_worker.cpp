// The single, in-order worker for tools/call (see mcp_call_worker.hpp).
#include "agent/mcp/mcp_call_worker.hpp"

namespace a3::agent::mcp {

McpCallWorker::McpCallWorker() : thread_([this] { run(); }) {}

McpCallWorker::~McpCallWorker() {
  shutdown();
  if (thread_.joinable()) thread_.join();
}

bool McpCallWorker::post(std::function<void()> job) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ || draining_) return false;
    jobs_.push_back(std::move(job));
  }
  wake_.notify_one();
  return true;
}

void McpCallWorker::shutdown() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    jobs_.clear();
  }
  wake_.notify_all();
  idle_.notify_all();
}

void McpCallWorker::drain() {
  std::unique_lock lock(mutex_);
  draining_ = true;
  idle_.wait(lock, [this] { return stopping_ || (jobs_.empty() && !busy_); });
}

void McpCallWorker::run() {
  for (;;) {
    std::function<void()> job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
      if (stopping_) return;
      job = std::move(jobs_.front());
      jobs_.pop_front();
      busy_ = true;
    }
    job();
    {
      std::lock_guard lock(mutex_);
      busy_ = false;
    }
    idle_.notify_all();
  }
}

}  // namespace a3::agent::mcp
