// One slice's piecewise-constant n_t process.
#include "linkemu/slice_state_process.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace a3::linkemu {
namespace {

RegimeTiming regime_timing(const SliceProfile& profile, const ProcessTiming& timing) {
  RegimeTiming t;
  t.degraded_share = profile.degraded_share;
  t.degraded_dwell_mean_s = timing.degraded_dwell_mean_s;
  t.normal_dwell_mean_s = timing.normal_dwell_mean_s(profile.degraded_share);
  t.min_dwell_s = timing.min_dwell_s;
  return t;
}

}  // namespace

std::string slice_stream_name(Slice slice, const char* term) {
  return std::string("linkemu/") + to_string(slice) + "/" + term;
}

SliceStateProcess::SliceStateProcess(const SliceProfile& profile, const ProcessTiming& timing,
                                     const common::RngStreams& streams, StartRegime start,
                                     int64_t start_us, DegradationWindows forced)
    : profile_(profile),
      redraw_mean_s_(timing.redraw_mean_s),
      regime_(streams.stream(slice_stream_name(profile.slice, "regime")),
              regime_timing(profile, timing), start, start_us),
      redraw_rng_(streams.stream(slice_stream_name(profile.slice, "redraw"))),
      lat_rng_(streams.stream(slice_stream_name(profile.slice, "lat_ms"))),
      jitter_rng_(streams.stream(slice_stream_name(profile.slice, "jitter_ms"))),
      loss_rng_(streams.stream(slice_stream_name(profile.slice, "loss_pct"))),
      throughput_rng_(streams.stream(slice_stream_name(profile.slice, "throughput_mbps"))),
      edge_rng_(streams.stream(slice_stream_name(profile.slice, "edge_load"))),
      forced_(std::move(forced)) {
  std::sort(forced_.begin(), forced_.end());
  state_.slice = profile.slice;
  redraw(start_us);
  next_redraw_us_ = start_us + draw_redraw_interval_us();
  segment_end_us_ = segment_end_after(start_us);
}

bool SliceStateProcess::forced_at(int64_t t_us) const {
  for (const auto& [start, end] : forced_) {
    if (t_us >= start && t_us < end) return true;
  }
  return false;
}

int64_t SliceStateProcess::next_forced_boundary_after(int64_t t_us) const {
  int64_t next = std::numeric_limits<int64_t>::max();
  for (const auto& [start, end] : forced_) {
    if (start > t_us) next = std::min(next, start);
    if (end > t_us) next = std::min(next, end);
  }
  return next;
}

int64_t SliceStateProcess::segment_end_after(int64_t t_us) const {
  return std::min({next_redraw_us_, regime_.episode_end_us(), next_forced_boundary_after(t_us)});
}

int64_t SliceStateProcess::draw_redraw_interval_us() {
  return std::max<int64_t>(1, std::llround(redraw_rng_.exponential(redraw_mean_s_) * 1e6));
}

void SliceStateProcess::redraw(int64_t t_us) {
  const bool degraded = regime_.degraded() || forced_at(t_us);
  const SliceProfile& p = profile_;
  state_.degraded = degraded;
  state_.lat_ms = p.lat_ms.sample_ms(lat_rng_, degraded);
  state_.jitter_ms =
      p.jitter_ms.ratio_to_lat * state_.lat_ms * sample_lognormal_mean_cv(jitter_rng_, 1.0, p.jitter_ms.cv);
  state_.loss_pct = std::min(
      100.0, sample_lognormal_mean_cv(loss_rng_,
                                      degraded ? p.loss_pct.degraded_mean : p.loss_pct.normal_mean,
                                      p.loss_pct.cv));
  state_.throughput_mbps = sample_lognormal_mean_cv(
      throughput_rng_, degraded ? p.throughput_mbps.degraded_mean : p.throughput_mbps.normal_mean,
      p.throughput_mbps.cv);
  state_.edge_load = sample_beta_mean(
      edge_rng_, degraded ? p.edge_load.degraded_mean : p.edge_load.normal_mean,
      degraded ? p.edge_load.degraded_concentration : p.edge_load.normal_concentration);
}

const NetworkState& SliceStateProcess::state_at(int64_t t_us) {
  while (t_us >= segment_end_us_) {
    const int64_t change_us = segment_end_us_;
    if (change_us >= regime_.episode_end_us()) regime_.advance_to(change_us);
    redraw(change_us);
    if (change_us >= next_redraw_us_) next_redraw_us_ = change_us + draw_redraw_interval_us();
    segment_end_us_ = segment_end_after(change_us);
  }
  return state_;
}

}  // namespace a3::linkemu
