// BatchPool: every item of every batch runs exactly once, on all workers, and run() returns
// only when the batch is done.
#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <thread>
#include <vector>

#include "common/batch_pool.hpp"

namespace a3::common {
namespace {

TEST(BatchPool, EveryItemRunsExactlyOncePerBatch) {
  BatchPool pool(3);
  EXPECT_EQ(pool.workers(), 3u);
  for (std::size_t count : {0u, 1u, 2u, 7u, 1000u}) {
    std::vector<std::atomic<int>> runs(count);
    pool.run(count, [&](std::size_t item, std::size_t worker) {
      ASSERT_LT(worker, 3u);
      runs[item].fetch_add(1);
    });
    for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(runs[i].load(), 1) << "item " << i;
  }
}

TEST(BatchPool, RunReturnsOnlyWhenTheBatchIsDone) {
  BatchPool pool(2);
  for (int batch = 0; batch < 200; ++batch) {
    std::atomic<int> finished{0};
    pool.run(4, [&](std::size_t, std::size_t) {
      std::this_thread::yield();
      finished.fetch_add(1);
    });
    ASSERT_EQ(finished.load(), 4) << "batch " << batch;
  }
}

TEST(BatchPool, WorkersShareTheBatchAndTheCallerIsWorkerZero) {
  BatchPool pool(2);
  std::mutex m;
  std::set<std::size_t> workers;
  const auto caller = std::this_thread::get_id();
  std::atomic<bool> caller_is_zero{true};
  pool.run(64, [&](std::size_t, std::size_t worker) {
    if ((std::this_thread::get_id() == caller) != (worker == 0)) caller_is_zero = false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::lock_guard<std::mutex> lock(m);
    workers.insert(worker);
  });
  EXPECT_TRUE(caller_is_zero.load());
  EXPECT_EQ(workers.size(), 2u);  // 64 sleeping items: both workers take some
}

TEST(BatchPool, ZeroMeansOneWorkerPerHardwareThread) {
  BatchPool pool(0);
  EXPECT_EQ(pool.workers(), std::max(1u, std::thread::hardware_concurrency()));
  BatchPool single(1);
  std::vector<std::size_t> order;
  single.run(5, [&](std::size_t item, std::size_t) { order.push_back(item); });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
}

}  // namespace
}  // namespace a3::common

namespace a3::common {
namespace {

TEST(BatchPool, StartReturnsAtOnceAndFinishCompletesTheBatch) {
  BatchPool pool(2);
  for (int batch = 0; batch < 50; ++batch) {
    std::vector<std::atomic<int>> runs(100);
    std::atomic<int> done{0};
    pool.start(100, [&](std::size_t item, std::size_t) {
      runs[item].fetch_add(1);
      done.fetch_add(1);
    });
    // The caller is free until finish(): the other worker may already be on the batch.
    int caller_work = 0;
    for (int i = 0; i < 1000; ++i) caller_work += i % 7;
    pool.finish();
    EXPECT_EQ(done.load(), 100);
    for (auto& r : runs) EXPECT_EQ(r.load(), 1);
    EXPECT_GT(caller_work, 0);
  }
}

TEST(BatchPool, AStartedBatchRunsWithoutTheCaller) {
  BatchPool pool(2);
  std::atomic<int> done{0};
  pool.start(3, [&](std::size_t, std::size_t worker) {
    EXPECT_EQ(worker, 1u);  // the caller is sleeping: only worker 1 can take items
    done.fetch_add(1);
  });
  for (int i = 0; i < 2000 && done.load() < 3; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(done.load(), 3);
  pool.finish();
}

}  // namespace
}  // namespace a3::common
