// Piecewise-constant replay of a recorded trace.
#include "linkemu/trace_replay.hpp"

#include <limits>

namespace a3::linkemu {

TraceReplay::TraceReplay(NetworkTrace trace, int64_t start_us, bool loop)
    : trace_(std::move(trace)), loop_(loop), cycle_start_us_(start_us) {}

NetworkState TraceReplay::state_at(Slice, int64_t t_us) {
  for (;;) {
    const int64_t next = next_change_us(Slice::kEmbb);
    if (t_us < next) break;
    if (index_ + 1 < trace_.points.size()) {
      ++index_;
    } else {  // looping: the next pass starts
      cycle_start_us_ += trace_.duration_us();
      index_ = 0;
    }
  }
  return trace_.points[index_].state;
}

int64_t TraceReplay::next_change_us(Slice) const {
  if (index_ + 1 < trace_.points.size()) return cycle_start_us_ + trace_.points[index_ + 1].t_us;
  if (!loop_) return std::numeric_limits<int64_t>::max();
  return cycle_start_us_ + trace_.duration_us();
}

std::string TraceReplay::describe() const {
  return "trace replay of " + (trace_.source.empty() ? std::string("a trace") : trace_.source) +
         " (" + std::to_string(trace_.points.size()) + " points" + (loop_ ? ", looping" : "") + ")";
}

}  // namespace a3::linkemu
