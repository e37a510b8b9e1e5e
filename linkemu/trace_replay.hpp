// Replays a NetworkTrace as the source of n_t: point i holds from its time until the next
// point's, the last one for good (or, looping, for last_hold before the trace starts over;
// before the first point's time, the first point holds).
// The trace decides the slice; switch requests are refused while it plays.
#pragma once

#include <cstddef>

#include "linkemu/network_state_source.hpp"
#include "linkemu/network_trace.hpp"

namespace a3::linkemu {

class TraceReplay final : public NetworkStateSource {
 public:
  // Trace time 0 is start_us.
  TraceReplay(NetworkTrace trace, int64_t start_us, bool loop);

  NetworkState state_at(Slice slice, int64_t t_us) override;
  int64_t next_change_us(Slice slice) const override;
  bool dictates_slice() const override { return true; }
  std::string describe() const override;

 private:
  NetworkTrace trace_;
  bool loop_;
  std::size_t index_ = 0;
  int64_t cycle_start_us_;  // start of the current pass through the trace
};

}  // namespace a3::linkemu
