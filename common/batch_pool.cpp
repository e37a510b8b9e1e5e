// Batch thread pool.
#include "common/batch_pool.hpp"

#include <algorithm>
#include <cstdint>

namespace a3::common {

BatchPool::BatchPool(std::size_t workers) {
  if (workers == 0) workers = std::max(1u, std::thread::hardware_concurrency());
  for (std::size_t w = 1; w < workers; ++w) threads_.emplace_back([this, w] { work(w); });
}

BatchPool::~BatchPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  start_cv_.notify_all();
  for (auto& t : threads_) t.join();
}

void BatchPool::drain(std::size_t worker) {
  while (true) {
    std::size_t item;
    const ItemFn* fn;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (next_item_ >= count_) return;
      item = next_item_++;
      fn = &fn_;
    }
    (*fn)(item, worker);
  }
}

void BatchPool::work(std::size_t worker) {
  uint64_t seen = 0;
  while (true) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_cv_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
      ++busy_workers_;
    }
    drain(worker);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      --busy_workers_;
    }
    done_cv_.notify_all();
  }
}

void BatchPool::start(std::size_t count, ItemFn fn) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    fn_ = std::move(fn);
    count_ = count;
    next_item_ = 0;
    ++generation_;
  }
  start_cv_.notify_all();
}

void BatchPool::finish() {
  drain(0);
  std::unique_lock<std::mutex> lock(mutex_);
  done_cv_.wait(lock, [&] { return busy_workers_ == 0 && next_item_ >= count_; });
}

void BatchPool::run(std::size_t count, ItemFn fn) {
  start(count, std::move(fn));
  finish();
}

}  // namespace a3::common
