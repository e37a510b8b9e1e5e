// A fixed pool of worker threads that runs one batch of independent items at a time:
// fn(item, worker) is called for every item in [0, count). The calling thread is worker 0: it
// may start() a batch, do other work (read the next batch, consume the previous one) while the
// other workers begin, then finish() helps with what is left and returns when the batch is
// done. Callers consume a batch's results in item order afterwards, so output stays
// deterministic and memory stays bounded by the batch size.
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

  // Runs fn over [0, count) and returns when done. fn must not throw (catch inside; a thrown
  // exception terminates).
  void run(std::size_t count, ItemFn fn);
  // The same in two steps: start() hands the batch to the other workers and returns at once;
  // finish() works on it as worker 0 and returns when every item is done. A batch must be
  // finished before the next one starts.
  void start(std::size_t count, ItemFn fn);
  void finish();

 private:
  void work(std::size_t worker);
  void drain(std::size_t worker);

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_cv_, done_cv_;
  ItemFn fn_;
  std::size_t count_ = 0;
  std::size_t next_item_ = 0;
  std::size_t busy_workers_ = 0;
  uint64_t generation_ = 0;
  bool stopping_ = false;
};

}  // namespace a3::common
