// An ordered queue of timers (time, insertion order): the deterministic core shared by
// both executors. Not thread-safe; executors lock around it where needed.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <unordered_map>

#include "common/executor.hpp"

namespace a3::common {

class TimerQueue {
 public:
  struct Due {
    TimerId id;
    int64_t time_us;
    int64_t period_us;  // 0: a one-shot timer
    // Shared so a callback may cancel its own timer (or add others) while it runs.
    std::shared_ptr<std::function<void()>> fn;
  };

  TimerId add(int64_t first_us, int64_t period_us, std::function<void()> fn);
  void cancel(TimerId id);
  // Earliest pending time, if any.
  std::optional<int64_t> next_time_us() const;
  // Removes the earliest timer due at or before t_us and returns it; a periodic timer is
  // re-armed for its next period before its callback runs. Returns nothing when none is due.
  std::optional<Due> pop_due(int64_t t_us);
  // Called after a popped one-shot timer's callback ran, to free it.
  void finish(const Due& due);
  std::size_t size() const { return timers_.size(); }

 private:
  struct Timer {
    int64_t period_us;
    std::shared_ptr<std::function<void()>> fn;
  };
  struct Key {
    int64_t time_us;
    uint64_t seq;
    bool operator<(const Key& o) const {
      return time_us != o.time_us ? time_us < o.time_us : seq < o.seq;
    }
  };
  std::map<Key, TimerId> order_;
  std::unordered_map<TimerId, std::pair<Key, Timer>> timers_;
  uint64_t next_seq_ = 0;
  TimerId next_id_ = 1;
};

}  // namespace a3::common
