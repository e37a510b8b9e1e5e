// Deterministic timer ordering by (time, insertion sequence), without steady-state allocation.
#include "common/timer_queue.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace a3::common {
namespace {

// std::push_heap / pop_heap build a max-heap: "greater" puts the earliest entry on top.
// A function object, not a function pointer, so the heap operations inline the comparison.
struct Later {
  template <typename Entry>
  bool operator()(const Entry& a, const Entry& b) const {
    return a.time_us != b.time_us ? a.time_us > b.time_us : a.seq > b.seq;
  }
};
constexpr Later later{};

}  // namespace

uint32_t TimerQueue::take_slot() {
  if (!free_slots_.empty()) {
    const uint32_t slot = free_slots_.back();
    free_slots_.pop_back();
    return slot;
  }
  if (slots_.size() > kSlotMask) {
    throw std::length_error("TimerQueue: more than " + std::to_string(kSlotMask) + " pending timers");
  }
  slots_.emplace_back();
  return static_cast<uint32_t>(slots_.size() - 1);
}

void TimerQueue::release_slot(uint32_t slot) {
  slots_[slot].id = 0;
  slots_[slot].fn = nullptr;
  free_slots_.push_back(slot);
  --live_;
}

void TimerQueue::push_entry(int64_t time_us, TimerId id) {
  const Entry entry{time_us, next_seq_++, id};
  // Appending keeps the FIFO sorted: its sequence numbers only grow, and so must its times.
  if (time_us == current_us_ && (fifo_head_ == fifo_.size() || fifo_.back().time_us <= time_us)) {
    fifo_.push_back(entry);
    return;
  }
  push_later(entry);
}

void TimerQueue::push_later(Entry entry) {
  if (!has_head_) {
    if (heap_.empty() || later(heap_.front(), entry)) {
      head_ = entry;
      has_head_ = true;
      return;
    }
  } else if (later(head_, entry)) {
    std::swap(head_, entry);  // the new entry is the earliest: the old head goes to the heap
  }
  heap_.push_back(entry);
  std::push_heap(heap_.begin(), heap_.end(), later);
}

void TimerQueue::drop_cancelled_top() const {
  if (has_head_ && !is_live(head_)) has_head_ = false;
  while (!heap_.empty() && !is_live(heap_.front())) {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    heap_.pop_back();
  }
  while (fifo_head_ < fifo_.size() && !is_live(fifo_[fifo_head_])) ++fifo_head_;
  if (fifo_head_ == fifo_.size()) {
    fifo_.clear();  // keeps its capacity
    fifo_head_ = 0;
  }
}

// Restores the heap after its top entry was replaced by a later one.
void TimerQueue::sift_top_down() {
  const std::size_t size = heap_.size();
  const Entry moving = heap_.front();
  std::size_t hole = 0;
  for (std::size_t child = 1; child < size; child = 2 * hole + 1) {
    if (child + 1 < size && later(heap_[child], heap_[child + 1])) ++child;
    if (!later(moving, heap_[child])) break;
    heap_[hole] = heap_[child];
    hole = child;
  }
  heap_[hole] = moving;
}

const TimerQueue::Entry* TimerQueue::earliest_later() const {
  if (has_head_) return &head_;
  return heap_.empty() ? nullptr : &heap_.front();
}

bool TimerQueue::fifo_first() const {
  if (fifo_head_ == fifo_.size()) return false;
  const Entry* later_one = earliest_later();
  return later_one == nullptr || later(*later_one, fifo_[fifo_head_]);
}

// Cancelled entries wait in the heap until they reach the top; when they outnumber the live
// ones (timeouts re-armed far ahead, say), the heap is rebuilt without them.
void TimerQueue::compact_if_mostly_cancelled() {
  if (heap_.size() < 64 || heap_.size() < 2 * live_) return;
  heap_.erase(std::remove_if(heap_.begin(), heap_.end(), [this](const Entry& e) { return !is_live(e); }),
              heap_.end());
  std::make_heap(heap_.begin(), heap_.end(), later);
}

TimerId TimerQueue::add(int64_t first_us, int64_t period_us, std::function<void()>&& fn) {
  const uint32_t slot = take_slot();
  const TimerId id = (next_serial_++ << kSlotBits) | slot;
  slots_[slot].id = id;
  slots_[slot].period_us = period_us;
  slots_[slot].fn.swap(fn);  // the free slot's callable is empty
  ++live_;
  push_entry(first_us, id);
  return id;
}

void TimerQueue::cancel(TimerId id) {
  const TimerId slot = id & kSlotMask;
  if (id == 0 || slot >= slots_.size() || slots_[slot].id != id) return;
  release_slot(static_cast<uint32_t>(slot));
  compact_if_mostly_cancelled();
}

std::optional<int64_t> TimerQueue::next_time_us() const {
  drop_cancelled_top();
  if (fifo_first()) return fifo_[fifo_head_].time_us;
  if (const Entry* later_one = earliest_later()) return later_one->time_us;
  return std::nullopt;
}

std::optional<TimerQueue::Due> TimerQueue::pop_due(int64_t t_us) {
  std::optional<Due> due(std::in_place);
  if (!pop_due(t_us, *due)) due.reset();
  return due;
}

bool TimerQueue::pop_due(int64_t t_us, Due& due) {
  drop_cancelled_top();
  Entry entry{};
  bool rearmed = false;
  if (fifo_first()) {
    if (fifo_[fifo_head_].time_us > t_us) return false;
    entry = fifo_[fifo_head_++];
  } else if (has_head_) {
    if (head_.time_us > t_us) return false;
    entry = head_;
    has_head_ = false;
  } else {
    if (heap_.empty() || heap_.front().time_us > t_us) return false;
    entry = heap_.front();
    const int64_t period_us = slots_[entry.id & kSlotMask].period_us;
    if (period_us > 0) {
      // Re-armed in place: one pass down the heap instead of a pop and a push.
      heap_.front() = Entry{entry.time_us + period_us, next_seq_++, entry.id};
      sift_top_down();
      rearmed = true;
    } else {
      std::pop_heap(heap_.begin(), heap_.end(), later);
      heap_.pop_back();
    }
  }
  current_us_ = entry.time_us;
  Slot& slot = slots_[entry.id & kSlotMask];
  if (slot.period_us > 0 && !rearmed) push_entry(entry.time_us + slot.period_us, entry.id);
  due.id = entry.id;
  due.time_us = entry.time_us;
  due.period_us = slot.period_us;
  due.fn.swap(slot.fn);  // `due` came back from finish() empty
  return true;
}

void TimerQueue::finish(Due& due) {
  const uint32_t slot = static_cast<uint32_t>(due.id & kSlotMask);
  const bool live = slot < slots_.size() && slots_[slot].id == due.id;  // not cancelled while it ran
  if (live && due.period_us > 0) {
    slots_[slot].fn.swap(due.fn);
  } else if (live) {
    release_slot(slot);
  }
  due.fn = nullptr;  // a one-shot's callable (or a cancelled one's) goes now, not at the next pop
}

}  // namespace a3::common
