// Slice profiles: the compiled-in file parses, names SPEC §6's figures as its targets, its
// fitted parameters reproduce them (in closed form and by sampling ≥ 100k draws per slice,
// within 5 %), the fit regenerates the file's numbers, and bad files are refused with the
// field named.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/json_file.hpp"
#include "common/rng.hpp"
#include "linkemu/distributions.hpp"
#include "linkemu/profile_fit.hpp"
#include "linkemu/slice_profile.hpp"
#include "tests/linkemu/linkemu_test_util.hpp"

namespace a3::linkemu {
namespace {

using test::relative_error;
using test::spec_rows;

TEST(SliceProfiles, CompiledInTargetsAreSpecSection6) {
  const SliceProfiles& profiles = default_slice_profiles();
  for (const auto& row : spec_rows()) {
    const CorpusTargets& t = profiles.at(row.slice).targets;
    SCOPED_TRACE(to_string(row.slice));
    EXPECT_DOUBLE_EQ(t.lat_mean_ms, row.lat_mean_ms);
    EXPECT_DOUBLE_EQ(t.lat_median_ms, row.lat_median_ms);
    EXPECT_DOUBLE_EQ(t.lat_p90_ms, row.lat_p90_ms);
    EXPECT_DOUBLE_EQ(t.jitter_mean_ms, row.jitter_mean_ms);
    EXPECT_DOUBLE_EQ(t.loss_mean_pct, row.loss_mean_pct);
    EXPECT_DOUBLE_EQ(t.throughput_mean_mbps, row.throughput_mean_mbps);
    EXPECT_DOUBLE_EQ(t.edge_load_mean, row.edge_load_mean);
  }
}

TEST(SliceProfiles, FittedLatencyMixtureHasTheTargetMeanMedianAndP90) {
  for (const auto& row : spec_rows()) {
    const SliceProfile& p = default_slice_profiles().at(row.slice);
    SCOPED_TRACE(to_string(row.slice));
    const double w = p.degraded_share;
    // The file holds 6 significant digits.
    EXPECT_LT(relative_error(p.lat_ms.mean_ms(w), row.lat_mean_ms), 1e-4);
    EXPECT_LT(relative_error(p.lat_ms.quantile_ms(0.5, w), row.lat_median_ms), 1e-4);
    EXPECT_LT(relative_error(p.lat_ms.quantile_ms(0.9, w), row.lat_p90_ms), 1e-4);
    // Time averages of the other terms over both regimes.
    const auto average = [w](double normal, double degraded) { return (1 - w) * normal + w * degraded; };
    EXPECT_LT(relative_error(average(p.loss_pct.normal_mean, p.loss_pct.degraded_mean), row.loss_mean_pct), 1e-4);
    EXPECT_LT(relative_error(average(p.throughput_mbps.normal_mean, p.throughput_mbps.degraded_mean),
                             row.throughput_mean_mbps), 1e-4);
    EXPECT_LT(relative_error(average(p.edge_load.normal_mean, p.edge_load.degraded_mean), row.edge_load_mean), 1e-4);
    EXPECT_LT(relative_error(p.jitter_ms.ratio_to_lat * row.lat_mean_ms, row.jitter_mean_ms), 1e-4);
    // The degraded regime is worse on every term.
    EXPECT_GT(p.lat_ms.degraded_factor, 1.0);
    EXPECT_GT(p.loss_pct.degraded_mean, p.loss_pct.normal_mean);
    EXPECT_LT(p.throughput_mbps.degraded_mean, p.throughput_mbps.normal_mean);
    EXPECT_GT(p.edge_load.degraded_mean, 0.8);
  }
}

TEST(SliceProfiles, RefittingReproducesTheFile) {
  const SliceProfiles& file = default_slice_profiles();
  const SliceProfiles refit = fit_slice_profiles(file);
  for (Slice slice : kAllSlices) {
    SCOPED_TRACE(to_string(slice));
    const SliceProfile& a = file.at(slice);
    const SliceProfile& b = refit.at(slice);
    EXPECT_LT(relative_error(a.lat_ms.normal_median_ms, b.lat_ms.normal_median_ms), 1e-5);
    EXPECT_LT(relative_error(a.lat_ms.sigma, b.lat_ms.sigma), 1e-5);
    EXPECT_LT(relative_error(a.lat_ms.degraded_factor, b.lat_ms.degraded_factor), 1e-5);
    EXPECT_LT(relative_error(a.jitter_ms.ratio_to_lat, b.jitter_ms.ratio_to_lat), 1e-5);
    EXPECT_LT(relative_error(a.loss_pct.normal_mean, b.loss_pct.normal_mean), 1e-5);
    EXPECT_LT(relative_error(a.throughput_mbps.normal_mean, b.throughput_mbps.normal_mean), 1e-5);
    EXPECT_LT(relative_error(a.edge_load.normal_mean, b.edge_load.normal_mean), 1e-5);
  }
}

// The check: generated latencies per slice match SPEC §6 within 5 % over ≥ 100k
// samples; and the other terms' means likewise. Each draw picks the regime with the
// slice's degraded share, as the time average of the regime process does.
TEST(SliceProfiles, SampledTermsMatchSpecWithinFivePercent) {
  constexpr int kSamples = 200000;
  const common::RngStreams streams(2025);
  for (const auto& row : spec_rows()) {
    const SliceProfile& p = default_slice_profiles().at(row.slice);
    SCOPED_TRACE(to_string(row.slice));
    common::Rng rng = streams.stream(std::string("test/") + to_string(row.slice));
    std::vector<double> lat, jitter, loss, throughput, edge;
    for (int i = 0; i < kSamples; ++i) {
      const bool degraded = rng.bernoulli(p.degraded_share);
      const double l = p.lat_ms.sample_ms(rng, degraded);
      lat.push_back(l);
      jitter.push_back(p.jitter_ms.ratio_to_lat * l * sample_lognormal_mean_cv(rng, 1.0, p.jitter_ms.cv));
      loss.push_back(sample_lognormal_mean_cv(
          rng, degraded ? p.loss_pct.degraded_mean : p.loss_pct.normal_mean, p.loss_pct.cv));
      throughput.push_back(sample_lognormal_mean_cv(
          rng, degraded ? p.throughput_mbps.degraded_mean : p.throughput_mbps.normal_mean,
          p.throughput_mbps.cv));
      edge.push_back(sample_beta_mean(rng, degraded ? p.edge_load.degraded_mean : p.edge_load.normal_mean,
                                      degraded ? p.edge_load.degraded_concentration
                                               : p.edge_load.normal_concentration));
    }
    EXPECT_LT(relative_error(test::mean_of(lat), row.lat_mean_ms), 0.05) << test::mean_of(lat);
    EXPECT_LT(relative_error(test::quantile_of(lat, 0.5), row.lat_median_ms), 0.05);
    EXPECT_LT(relative_error(test::quantile_of(lat, 0.9), row.lat_p90_ms), 0.05);
    EXPECT_LT(relative_error(test::mean_of(jitter), row.jitter_mean_ms), 0.05);
    EXPECT_LT(relative_error(test::mean_of(loss), row.loss_mean_pct), 0.05);
    EXPECT_LT(relative_error(test::mean_of(throughput), row.throughput_mean_mbps), 0.05);
    EXPECT_LT(relative_error(test::mean_of(edge), row.edge_load_mean), 0.05);
    for (double e : edge) ASSERT_TRUE(e >= 0.0 && e <= 1.0) << e;
  }
}

TEST(SliceProfiles, FitFindsAMixtureForOtherTargetsAndRefusesImpossibleOnes) {
  const LatencyMixture m = fit_latency_mixture(30.0, 20.0, 45.0, 0.05);
  EXPECT_LT(relative_error(m.mean_ms(0.05), 30.0), 1e-6);
  EXPECT_LT(relative_error(m.quantile_ms(0.5, 0.05), 20.0), 1e-6);
  EXPECT_LT(relative_error(m.quantile_ms(0.9, 0.05), 45.0), 1e-6);
  // A mean below the median cannot come from a right-skewed mixture.
  EXPECT_THROW(fit_latency_mixture(10.0, 20.0, 45.0, 0.05), std::invalid_argument);
}

TEST(SliceProfiles, JsonRoundTrip) {
  const SliceProfiles& a = default_slice_profiles();
  const SliceProfiles b = parse_slice_profiles(nlohmann::json::parse(to_json(a).dump()), "round trip: ");
  EXPECT_EQ(to_json(a).dump(), to_json(b).dump());
  EXPECT_EQ(a.description, b.description);
}

// Edits the compiled-in document at a JSON pointer and returns the parse error.
std::string error_after(const std::string& pointer, const nlohmann::json& value, bool erase = false) {
  nlohmann::json doc = nlohmann::json::parse(default_slice_profiles_json());
  if (erase) {
    const nlohmann::json::json_pointer ptr(pointer);
    doc[ptr.parent_pointer()].erase(ptr.back());
  } else {
    doc[nlohmann::json::json_pointer(pointer)] = value;
  }
  try {
    parse_slice_profiles(doc, "profiles.json: ");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(SliceProfiles, BadFilesAreRefusedNamingTheField) {
  EXPECT_EQ(error_after("/slices/eMBB/lat_ms/sigma", -0.5),
            "profiles.json: /slices/eMBB/lat_ms/sigma: -0.5 is outside (0, inf)");
  EXPECT_EQ(error_after("/slices/mMTC/edge_load/degraded_mean", 1.2),
            "profiles.json: /slices/mMTC/edge_load/degraded_mean: 1.2 is outside (0, 1)");
  EXPECT_EQ(error_after("/slices/URLLC/loss_pct/family", "gamma"),
            "profiles.json: /slices/URLLC/loss_pct/family: 'gamma' is not supported (expected 'lognormal')");
  EXPECT_EQ(error_after("/slices/URLLC", nullptr, true), "profiles.json: /slices/URLLC: missing");
  EXPECT_EQ(error_after("/slices/eMBB/targets/lat_ms/p90", "25"),
            "profiles.json: /slices/eMBB/targets/lat_ms/p90: expected a number, got string");
  EXPECT_NE(error_after("/slices/5G", nlohmann::json::object()).find("/slices/5G: unknown slice '5G'"),
            std::string::npos);
  EXPECT_EQ(error_after("/process/min_dwell_s", 40.0),
            "profiles.json: /process: degraded_dwell_mean_s must exceed min_dwell_s");
}

}  // namespace
}  // namespace a3::linkemu
