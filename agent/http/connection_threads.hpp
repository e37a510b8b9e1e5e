// httplib's task queue for GuardedServer: each accepted connection runs on a thread of its own,
// so a slow client holds only its own thread. At most `max_threads` run at once; a connection
// beyond that is run on the accepting thread with refused_at_once() true, and is closed unread.
// Finished threads are joined as new ones start and at shutdown.
#pragma once

#include <httplib.h>

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <list>
#include <mutex>
#include <thread>
#include <vector>

namespace a3::agent::http {

class ConnectionThreads final : public httplib::TaskQueue {
 public:
  explicit ConnectionThreads(std::size_t max_threads);
  ~ConnectionThreads() override;

  void enqueue(std::function<void()> connection) override;
  void shutdown() override;  // waits for every connection to end
  void on_idle() override;   // joins finished threads

  // True on the thread running a connection the queue had no room for.
  static bool refused_at_once();

 private:
  void join_finished();

  struct Worker {
    std::thread thread;
    bool finished = false;
  };
  std::size_t max_threads_;
  std::mutex mutex_;
  std::list<Worker> workers_;
};

}  // namespace a3::agent::http
