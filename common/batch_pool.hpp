// A fixed pool of worker threads that runs one batch of independent items at a time:
// run(count, fn) calls fn(item, worker) for every item in [0, count) on all workers (the
// calling thread is worker 0) and returns when the batch is done. Callers consume the batch's
// results in item order afterwards, so output stays deterministic and memory stays bounded
// by the batch size.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace a3::common {

class BatchPool {
 public:
  using ItemFn = std::function<void(std::size_t item, std::size_t worker)>;

  // workers >= 1 (0: one per hardware thread).
  explicit BatchPool(std::size_t workers);
  ~BatchPool();
  BatchPool(const BatchPool&) = delete;
  BatchPool& operator=(const BatchPool&) = delete;

  std::size_t workers() const { return threads_.size() + 1; }

  // Runs fn over [0, count). fn must not throw (catch inside; a thrown exception terminates).
  void run(std::size_t count, const ItemFn& fn);

 private:
  void work(std::size_t worker);
  void drain(std::size_t worker);

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_cv_, done_cv_;
  const ItemFn* fn_ = nullptr;
  std::size_t count_ = 0;
  std::size_t next_item_ = 0;
  std::size_t busy_workers_ = 0;
  uint64_t generation_ = 0;
  bool stopping_ = false;
};

}  // namespace a3::common
