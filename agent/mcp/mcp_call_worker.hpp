// One thread that runs an MCP client's tools/call requests one at a time, in the order they
// came, so that the transport keeps answering other messages (ping, tools/list) meanwhile.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

namespace a3::agent::mcp {

class McpCallWorker {
 public:
  McpCallWorker();
  ~McpCallWorker();  // shutdown(), then waits for the job in progress
  McpCallWorker(const McpCallWorker&) = delete;
  McpCallWorker& operator=(const McpCallWorker&) = delete;

  // Queues a job; false (and the job is not run) once shut down.
  bool post(std::function<void()> job);
  // Drops queued jobs and refuses new ones; the job in progress finishes. Idempotent.
  void shutdown();
  // Refuses new jobs and waits until every queued job has run.
  void drain();

 private:
  void run();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> jobs_;
  bool stopping_ = false;
  bool draining_ = false;
  bool busy_ = false;
  std::condition_variable idle_;
  std::thread thread_;
};

}  // namespace a3::agent::mcp
