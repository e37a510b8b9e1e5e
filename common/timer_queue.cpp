// Deterministic timer ordering by (time, insertion sequence).
#include "common/timer_queue.hpp"

namespace a3::common {

TimerId TimerQueue::add(int64_t first_us, int64_t period_us, std::function<void()> fn) {
  const TimerId id = next_id_++;
  const Key key{first_us, next_seq_++};
  order_.emplace(key, id);
  timers_.emplace(id, std::make_pair(key, Timer{period_us, std::make_shared<std::function<void()>>(std::move(fn))}));
  return id;
}

void TimerQueue::cancel(TimerId id) {
  auto it = timers_.find(id);
  if (it == timers_.end()) return;
  order_.erase(it->second.first);
  timers_.erase(it);
}

std::optional<int64_t> TimerQueue::next_time_us() const {
  if (order_.empty()) return std::nullopt;
  return order_.begin()->first.time_us;
}

std::optional<TimerQueue::Due> TimerQueue::pop_due(int64_t t_us) {
  if (order_.empty() || order_.begin()->first.time_us > t_us) return std::nullopt;
  const auto [key, id] = *order_.begin();
  order_.erase(order_.begin());
  auto& entry = timers_.at(id);
  if (entry.second.period_us > 0) {
    const Key next{key.time_us + entry.second.period_us, next_seq_++};
    entry.first = next;
    order_.emplace(next, id);
  }
  return Due{id, key.time_us, entry.second.period_us, entry.second.fn};
}

void TimerQueue::finish(const Due& due) {
  auto it = timers_.find(due.id);
  if (it != timers_.end() && it->second.second.period_us <= 0) timers_.erase(it);
}

}  // namespace a3::common
