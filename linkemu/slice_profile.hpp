// Slice profiles: per slice, the corpus statistics it is calibrated to (SPEC-alpha3.md §6)
// and the distributions of each term of n_t in the normal and the degraded regime; plus
// the timing of the network-state process. Read from JSON (slice_profiles.json is the
// default, compiled into the library).
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <string>
#include <string_view>

#include "linkemu/distributions.hpp"
#include "linkemu/network_state.hpp"

namespace a3::linkemu {

// SPEC §6 statistics of one slice.
struct CorpusTargets {
  double lat_mean_ms = 0.0;
  double lat_median_ms = 0.0;
  double lat_p90_ms = 0.0;
  double jitter_mean_ms = 0.0;
  double loss_mean_pct = 0.0;
  double throughput_mean_mbps = 0.0;
  double edge_load_mean = 0.0;
};

// jitter_ms = ratio_to_lat · lat_ms · (lognormal noise of mean 1 and the given cv).
struct JitterModel {
  double ratio_to_lat = 0.0;
  double cv = 0.0;
};

// A positive term, lognormal with a mean per regime and one coefficient of variation.
struct LognormalTerm {
  double normal_mean = 0.0;
  double degraded_mean = 0.0;
  double cv = 0.0;
};

// Edge load in [0, 1]: Beta with a mean and a concentration (α + β) per regime.
struct BetaTerm {
  double normal_mean = 0.5;
  double degraded_mean = 0.5;
  double normal_concentration = 1.0;
  double degraded_concentration = 1.0;
};

struct SliceProfile {
  Slice slice = Slice::kEmbb;
  CorpusTargets targets;
  double degraded_share = 0.0;  // long-run share of time in the degraded regime
  LatencyMixture lat_ms;
  JitterModel jitter_ms;
  LognormalTerm loss_pct;
  LognormalTerm throughput_mbps;
  BetaTerm edge_load;
};

// Timing of the network-state process (shared by the slices).
struct ProcessTiming {
  double redraw_mean_s = 2.0;          // mean time between new n_t values within a regime
  double degraded_dwell_mean_s = 30.0;  // mean length of a degraded episode
  double min_dwell_s = 5.0;            // no regime episode is shorter
  // Mean length of a normal episode: degraded_dwell_mean_s · (1 - w) / w (w = share).
  double normal_dwell_mean_s(double degraded_share) const;
};

struct SliceProfiles {
  std::string description;  // free text kept from the file
  std::array<SliceProfile, 3> slices;
  ProcessTiming timing;
  const SliceProfile& at(Slice slice) const { return slices[index_of(slice)]; }
  SliceProfile& at(Slice slice) { return slices[index_of(slice)]; }
};

// Parses and checks a profile document; `where` names it in errors (common::InputError).
SliceProfiles parse_slice_profiles(const nlohmann::json& document, const std::string& where);
SliceProfiles load_slice_profiles(const std::filesystem::path& path);
// The profiles of slice_profiles.json, compiled in.
const SliceProfiles& default_slice_profiles();
std::string_view default_slice_profiles_json();
// The document parse_slice_profiles reads (round trip), keys in the file's order.
nlohmann::ordered_json to_json(const SliceProfiles& profiles);

}  // namespace a3::linkemu
