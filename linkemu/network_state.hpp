// The 6G network vector n_t = (slice, lat_ms, jitter_ms, loss_pct, throughput_mbps,
// edge_load) of SPEC-alpha3.md §1, the three slices, and the "hard" test of SPEC §2.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "a3lcm/network_state_t.hpp"

namespace a3::linkemu {

enum class Slice : uint8_t { kUrllc = 0, kEmbb = 1, kMmtc = 2 };
inline constexpr std::array<Slice, 3> kAllSlices = {Slice::kUrllc, Slice::kEmbb, Slice::kMmtc};

// "URLLC" | "eMBB" | "mMTC" (the corpus spelling).
const char* to_string(Slice slice);
// Exact corpus spelling; throws std::invalid_argument naming the value and the choices.
Slice parse_slice(std::string_view text);
// The names, in kAllSlices order, and the names to slices (for command-line parsers).
std::vector<std::string> slice_names();
std::map<std::string, Slice> slice_by_name();
inline std::size_t index_of(Slice slice) { return static_cast<std::size_t>(slice); }

struct NetworkState {
  Slice slice = Slice::kEmbb;
  double lat_ms = 0.0;           // one-way latency (mean of the per-message samples)
  double jitter_ms = 0.0;        // standard deviation of the per-message latency
  double loss_pct = 0.0;         // message loss probability, percent
  double throughput_mbps = 0.0;  // link rate for serialization
  double edge_load = 0.0;        // edge-compute utilisation, [0, 1]
  bool degraded = false;         // in the degraded ("hard") regime
  bool operator==(const NetworkState&) const = default;
};

// SPEC §2: a turn is hard iff lat_ms > 40 or loss_pct >= 1 or throughput_mbps < 5 or
// edge_load > 0.8.
struct HardThresholds {
  double lat_ms_above = 40.0;
  double loss_pct_at_least = 1.0;
  double throughput_mbps_below = 5.0;
  double edge_load_above = 0.8;
};
bool is_hard(const NetworkState& state, const HardThresholds& thresholds = {});

a3lcm::network_state_t to_lcm(const NetworkState& state, int64_t utime_us,
                              const std::string& pending_slice);

}  // namespace a3::linkemu
