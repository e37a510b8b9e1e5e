// Slice names, the hard test, conversion to the LCM message.
#include "linkemu/network_state.hpp"

#include <stdexcept>

namespace a3::linkemu {

const char* to_string(Slice slice) {
  switch (slice) {
    case Slice::kUrllc: return "URLLC";
    case Slice::kEmbb: return "eMBB";
    case Slice::kMmtc: return "mMTC";
  }
  return "?";
}

Slice parse_slice(std::string_view text) {
  for (Slice slice : kAllSlices) {
    if (text == to_string(slice)) return slice;
  }
  throw std::invalid_argument("unknown slice '" + std::string(text) +
                              "' (expected URLLC, eMBB or mMTC)");
}

std::vector<std::string> slice_names() {
  std::vector<std::string> names;
  for (Slice slice : kAllSlices) names.emplace_back(to_string(slice));
  return names;
}

std::map<std::string, Slice> slice_by_name() {
  std::map<std::string, Slice> out;
  for (Slice slice : kAllSlices) out.emplace(to_string(slice), slice);
  return out;
}

bool is_hard(const NetworkState& state, const HardThresholds& t) {
  return state.lat_ms > t.lat_ms_above || state.loss_pct >= t.loss_pct_at_least ||
         state.throughput_mbps < t.throughput_mbps_below || state.edge_load > t.edge_load_above;
}

a3lcm::network_state_t to_lcm(const NetworkState& state, int64_t utime_us,
                              const std::string& pending_slice) {
  a3lcm::network_state_t m{};
  m.utime_us = utime_us;
  m.slice = to_string(state.slice);
  m.lat_ms = state.lat_ms;
  m.jitter_ms = state.jitter_ms;
  m.loss_pct = state.loss_pct;
  m.throughput_mbps = state.throughput_mbps;
  m.edge_load = state.edge_load;
  m.degraded = state.degraded;
  m.pending_slice = pending_slice;
  return m;
}

}  // namespace a3::linkemu
