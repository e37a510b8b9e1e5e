// The three slices' processes behind one NetworkStateSource.
#include "linkemu/synthetic_network.hpp"

namespace a3::linkemu {

SyntheticNetwork::SyntheticNetwork(const SliceProfiles& profiles,
                                   const common::RngStreams& streams, StartRegime start,
                                   int64_t start_us, DegradationWindows forced)
    : seed_(streams.master_seed()), forced_windows_(forced.size()) {
  for (Slice slice : kAllSlices) {
    processes_[index_of(slice)] = std::make_unique<SliceStateProcess>(
        profiles.at(slice), profiles.timing, streams, start, start_us, forced);
  }
}

NetworkState SyntheticNetwork::state_at(Slice slice, int64_t t_us) {
  return processes_[index_of(slice)]->state_at(t_us);
}

int64_t SyntheticNetwork::next_change_us(Slice slice) const {
  return processes_[index_of(slice)]->next_change_us();
}

std::string SyntheticNetwork::describe() const {
  return "seeded slice-profile process (seed " + std::to_string(seed_) + ")" +
         (forced_windows_ > 0 ? ", " + std::to_string(forced_windows_) + " scripted degradation window(s)" : "");
}

}  // namespace a3::linkemu
