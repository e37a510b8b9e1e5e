// Real-time scheduling for the link emulator's threads: while a ScopedRealtimePriority
// lives, the calling thread runs SCHED_FIFO, and threads it creates meanwhile inherit it
// (LCM's receive thread and the node's executor thread, when the node is started inside
// the scope). Under CPU load this is what keeps delivery on schedule: a SCHED_OTHER thread
// can wait several milliseconds for a CPU. Not in common/ yet; it belongs there.
#pragma once

namespace a3::linkemu {

class ScopedRealtimePriority {
 public:
  // priority 1..99; 0 does nothing. Throws std::runtime_error with a fix-it message when
  // the host does not allow it (needs root or CAP_SYS_NICE, or `ulimit -r`).
  explicit ScopedRealtimePriority(int priority);
  ~ScopedRealtimePriority();
  ScopedRealtimePriority(const ScopedRealtimePriority&) = delete;
  ScopedRealtimePriority& operator=(const ScopedRealtimePriority&) = delete;

 private:
  bool changed_ = false;
  int old_policy_ = 0;
  int old_priority_ = 0;
};

}  // namespace a3::linkemu
