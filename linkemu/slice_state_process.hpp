// The network vector n_t of one slice over time: piecewise constant, redrawn from the
// slice profile's distributions of the current regime at exponential intervals (mean
// redraw_mean_s) and at every regime change. Each term draws from its own named random
// stream; the value at time t depends only on the seed and t, not on when or how often it
// is asked for.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/rng.hpp"
#include "linkemu/network_state.hpp"
#include "linkemu/regime_process.hpp"
#include "linkemu/slice_profile.hpp"

namespace a3::linkemu {

// Windows [start, end) of forced degradation (a scenario's scripted outages), µs.
using DegradationWindows = std::vector<std::pair<int64_t, int64_t>>;

class SliceStateProcess {
 public:
  // forced: during these windows the process is in its degraded regime whatever the regime
  // process says (and n_t is redrawn when a window starts and ends).
  SliceStateProcess(const SliceProfile& profile, const ProcessTiming& timing,
                    const common::RngStreams& streams, StartRegime start, int64_t start_us,
                    DegradationWindows forced = {});

  // n_t at t_us. Times must not go backwards (an earlier t_us gives the current state).
  const NetworkState& state_at(int64_t t_us);
  // When the state last returned changes next.
  int64_t next_change_us() const { return segment_end_us_; }

 private:
  void redraw(int64_t t_us);
  int64_t draw_redraw_interval_us();
  bool forced_at(int64_t t_us) const;
  int64_t next_forced_boundary_after(int64_t t_us) const;
  int64_t segment_end_after(int64_t t_us) const;

  SliceProfile profile_;
  double redraw_mean_s_;
  RegimeProcess regime_;
  common::Rng redraw_rng_, lat_rng_, jitter_rng_, loss_rng_, throughput_rng_, edge_rng_;
  NetworkState state_;
  int64_t next_redraw_us_ = 0;
  int64_t segment_end_us_ = 0;
  DegradationWindows forced_;
};

// The random-stream name of one term of one slice, e.g. "linkemu/eMBB/lat_ms".
std::string slice_stream_name(Slice slice, const char* term);

}  // namespace a3::linkemu
