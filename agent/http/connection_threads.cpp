// A thread per connection, up to a limit (see connection_threads.hpp).
#include "agent/http/connection_threads.hpp"

namespace a3::agent::http {
namespace {

thread_local bool t_refused_at_once = false;

}  // namespace

ConnectionThreads::ConnectionThreads(std::size_t max_threads) : max_threads_(max_threads) {}

ConnectionThreads::~ConnectionThreads() { shutdown(); }

bool ConnectionThreads::refused_at_once() { return t_refused_at_once; }

void ConnectionThreads::enqueue(std::function<void()> connection) {
  join_finished();
  std::unique_lock lock(mutex_);
  if (workers_.size() >= max_threads_) {
    lock.unlock();
    t_refused_at_once = true;
    connection();
    t_refused_at_once = false;
    return;
  }
  Worker& worker = workers_.emplace_back();
  // The list keeps `worker` where it is; the thread marks it finished as its last act.
  worker.thread = std::thread([this, &worker, connection = std::move(connection)]() mutable {
    connection();
    connection = nullptr;
    std::lock_guard done(mutex_);
    worker.finished = true;
  });
}

void ConnectionThreads::join_finished() {
  std::list<Worker> finished;
  {
    std::lock_guard lock(mutex_);
    for (auto it = workers_.begin(); it != workers_.end();) {
      auto next = std::next(it);
      if (it->finished) finished.splice(finished.end(), workers_, it);
      it = next;
    }
  }
  for (Worker& worker : finished) worker.thread.join();
}

void ConnectionThreads::on_idle() { join_finished(); }

void ConnectionThreads::shutdown() {
  std::list<Worker> all;
  {
    std::lock_guard lock(mutex_);
    all.splice(all.end(), workers_);
  }
  for (Worker& worker : all) {
    if (worker.thread.joinable()) worker.thread.join();
  }
}

}  // namespace a3::agent::http
