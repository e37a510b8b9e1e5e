// An ordered queue of timers (time, insertion order): the deterministic core shared by
// both executors. Not thread-safe; executors lock around it where needed.
// Allocation-free in steady state: timers live in reused slots, the order is a binary heap
// in a reused vector (a cancelled timer's entry is dropped when it reaches the top), and a
// callback is moved, never copied (a std::function's small-buffer callable stays inline).
// Timers added for the time of the timer last popped (a bus delivery, a frame arbitrated
// "now") skip the heap: they wait in a FIFO, which is already in (time, insertion) order.
// A timer added for later but before everything in the heap (a CAN frame's end, 130 us on)
// waits in a slot of its own, the head, and moves into the heap only when an earlier one
// comes. pop_due takes the earliest of the FIFO's front, the head and the heap's top.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "common/executor.hpp"

namespace a3::common {

class TimerQueue {
 public:
  struct Due {
    TimerId id;
    int64_t time_us;
    int64_t period_us;  // 0: a one-shot timer
    // Held here while it runs, so a callback may cancel its own timer (or add others).
    std::function<void()> fn;
  };

  // Takes fn's callable (fn is left empty).
  TimerId add(int64_t first_us, int64_t period_us, std::function<void()>&& fn);
  void cancel(TimerId id);
  // Earliest pending time, if any.
  std::optional<int64_t> next_time_us() const;
  // Removes the earliest timer due at or before t_us and returns it; a periodic timer is
  // re-armed for its next period before its callback runs. Returns nothing when none is due.
  std::optional<Due> pop_due(int64_t t_us);
  // The same into `due` (empty, as finish() leaves it; the callable is swapped in from the
  // timer's slot); false when none is due.
  bool pop_due(int64_t t_us, Due& due);
  // Called after a popped timer's callback ran (or threw): frees a one-shot, gives a periodic
  // timer (unless cancelled meanwhile) its callback back; `due` is left empty, ready for reuse. Until then a periodic timer's next
  // period must not be popped (executors do not run the queue from inside a callback).
  void finish(Due& due);
  std::size_t size() const { return live_; }

 private:
  struct Slot {
    TimerId id = 0;  // 0: free
    int64_t period_us = 0;
    std::function<void()> fn;
  };
  struct Entry {
    int64_t time_us;
    uint64_t seq;
    TimerId id;
  };
  // A TimerId is (serial << kSlotBits) | slot: unique, increasing, and finds its slot.
  static constexpr unsigned kSlotBits = 24;
  static constexpr TimerId kSlotMask = (TimerId{1} << kSlotBits) - 1;

  uint32_t take_slot();
  void release_slot(uint32_t slot);
  bool is_live(const Entry& entry) const { return slots_[entry.id & kSlotMask].id == entry.id; }
  void push_entry(int64_t time_us, TimerId id);
  void push_later(Entry entry);
  void sift_top_down();
  void drop_cancelled_top() const;
  // The earliest of the head and the heap's top (without cancelled entries), if any.
  const Entry* earliest_later() const;
  // True when the FIFO's front comes before the head and the heap's top.
  bool fifo_first() const;
  void compact_if_mostly_cancelled();

  std::vector<Slot> slots_;
  std::vector<uint32_t> free_slots_;
  mutable std::vector<Entry> heap_;  // min-heap on (time_us, seq); may hold cancelled entries
  // When has_head_: an entry before every one in the heap (maybe cancelled).
  mutable Entry head_{};
  mutable bool has_head_ = false;
  // Entries in (time_us, seq) order from fifo_head_ on; may hold cancelled entries.
  mutable std::vector<Entry> fifo_;
  mutable std::size_t fifo_head_ = 0;
  int64_t current_us_ = INT64_MIN;  // the time of the timer last popped
  std::size_t live_ = 0;
  uint64_t next_seq_ = 0;
  uint64_t next_serial_ = 1;
};

}  // namespace a3::common
