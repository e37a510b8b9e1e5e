// Fitting a slice profile to its corpus statistics (SPEC-alpha3.md §6): the latency
// mixture so that its mean, median and P90 are the targets, and the normal-regime means of
// the other terms so that the time average over both regimes is the target mean.
#pragma once

#include "linkemu/distributions.hpp"
#include "linkemu/slice_profile.hpp"

namespace a3::linkemu {

// The LatencyMixture with degraded share w whose mean, median and P90 are the targets.
// Throws std::invalid_argument when no such mixture exists.
LatencyMixture fit_latency_mixture(double mean_ms, double median_ms, double p90_ms,
                                   double degraded_share);

// The profile with its fitted fields recomputed from `targets` and the design choices it
// holds (degraded share, degraded-regime means, spreads): lat_ms, jitter_ms.ratio_to_lat,
// and the normal_mean of loss_pct, throughput_mbps and edge_load.
SliceProfile fit_slice_profile(const SliceProfile& design);
SliceProfiles fit_slice_profiles(const SliceProfiles& design);

}  // namespace a3::linkemu
