// The seeded network-state process: one SliceStateProcess per slice, all running from the
// start, so that switching to a slice finds it in whatever regime it is in by then.
#pragma once

#include <array>
#include <memory>

#include "common/rng.hpp"
#include "linkemu/network_state_source.hpp"
#include "linkemu/slice_profile.hpp"
#include "linkemu/slice_state_process.hpp"

namespace a3::linkemu {

class SyntheticNetwork final : public NetworkStateSource {
 public:
  // forced: windows of forced degradation on every slice (times from the run's start).
  SyntheticNetwork(const SliceProfiles& profiles, const common::RngStreams& streams,
                   StartRegime start, int64_t start_us, DegradationWindows forced = {});

  NetworkState state_at(Slice slice, int64_t t_us) override;
  int64_t next_change_us(Slice slice) const override;
  bool dictates_slice() const override { return false; }
  std::string describe() const override;

 private:
  std::array<std::unique_ptr<SliceStateProcess>, 3> processes_;
  uint64_t seed_;
  std::size_t forced_windows_ = 0;
};

}  // namespace a3::linkemu
