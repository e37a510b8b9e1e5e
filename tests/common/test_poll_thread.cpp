// PollThread: asks its question every period until the answer is yes, and goes at once.
#include "common/poll_thread.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace a3::common {
namespace {

using namespace std::chrono_literals;

TEST(PollThread, PollsUntilTheAnswerIsYes) {
  std::atomic<int> polls{0};
  {
    const PollThread thread(1ms, [&polls] { return ++polls == 5; });
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (polls.load() < 5 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(1ms);
    std::this_thread::sleep_for(20ms);  // long enough for more polls, were there any
  }
  EXPECT_EQ(polls.load(), 5);
}

TEST(PollThread, GoesWithoutWaitingOutItsPeriod) {
  std::atomic<int> polls{0};
  const auto start = std::chrono::steady_clock::now();
  {
    const PollThread thread(60s, [&polls] {
      ++polls;
      return false;
    });
    while (polls.load() == 0) std::this_thread::sleep_for(1ms);
  }
  // The thread was in the middle of a 60 s wait: the destructor woke it.
  EXPECT_LT(std::chrono::steady_clock::now() - start, 30s);
  EXPECT_EQ(polls.load(), 1);
}

}  // namespace
}  // namespace a3::common
