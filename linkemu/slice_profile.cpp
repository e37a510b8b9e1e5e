// Slice-profile JSON: parsing with errors that name the file and field, and writing.
#include "linkemu/slice_profile.hpp"

#include <cmath>
#include <sstream>

#include "common/json_file.hpp"

namespace a3::linkemu {
namespace {

using common::InputError;
using nlohmann::json;

double number_in(const json& object, const std::string& key, const std::string& where, double lo,
                 double hi, bool lo_open, bool hi_open) {
  const double x = common::require_number(object, key, where);
  const bool above = lo_open ? x > lo : x >= lo;
  const bool below = hi_open ? x < hi : x <= hi;
  if (!above || !below) {
    std::ostringstream message;
    message << where << "/" << key << ": " << x << " is outside " << (lo_open ? "(" : "[") << lo
            << ", " << hi << (hi_open ? ")" : "]");
    throw InputError(message.str());
  }
  return x;
}

constexpr double kInf = HUGE_VAL;
double positive(const json& o, const std::string& k, const std::string& w) {
  return number_in(o, k, w, 0.0, kInf, true, true);
}
double non_negative(const json& o, const std::string& k, const std::string& w) {
  return number_in(o, k, w, 0.0, kInf, false, true);
}
double open_unit(const json& o, const std::string& k, const std::string& w) {
  return number_in(o, k, w, 0.0, 1.0, true, true);
}

void require_family(const json& object, const std::string& where, const std::string& family) {
  const std::string got = common::require_string(object, "family", where);
  if (got != family) {
    throw InputError(where + "/family: '" + got + "' is not supported (expected '" + family + "')");
  }
}

LognormalTerm parse_lognormal_term(const json& object, const std::string& where, double max_mean) {
  require_family(object, where, "lognormal");
  LognormalTerm term;
  term.normal_mean = number_in(object, "normal_mean", where, 0.0, max_mean, false, false);
  term.degraded_mean = number_in(object, "degraded_mean", where, 0.0, max_mean, false, false);
  term.cv = non_negative(object, "cv", where);
  return term;
}

SliceProfile parse_slice(const json& object, Slice slice, const std::string& where) {
  SliceProfile p;
  p.slice = slice;
  const std::string targets_where = where + "/targets";
  const json& targets = common::require_object(object, "targets", where);
  const json& lat_targets = common::require_object(targets, "lat_ms", targets_where);
  p.targets.lat_mean_ms = positive(lat_targets, "mean", targets_where + "/lat_ms");
  p.targets.lat_median_ms = positive(lat_targets, "median", targets_where + "/lat_ms");
  p.targets.lat_p90_ms = positive(lat_targets, "p90", targets_where + "/lat_ms");
  if (!(p.targets.lat_median_ms < p.targets.lat_p90_ms)) {
    throw InputError(targets_where + "/lat_ms: the median must be below the p90");
  }
  p.targets.jitter_mean_ms = non_negative(targets, "jitter_ms_mean", targets_where);
  p.targets.loss_mean_pct = number_in(targets, "loss_pct_mean", targets_where, 0, 100, false, false);
  p.targets.throughput_mean_mbps = positive(targets, "throughput_mbps_mean", targets_where);
  p.targets.edge_load_mean = open_unit(targets, "edge_load_mean", targets_where);

  p.degraded_share = number_in(object, "degraded_share", where, 0.0, 1.0, false, true);

  const std::string lat_where = where + "/lat_ms";
  const json& lat = common::require_object(object, "lat_ms", where);
  require_family(lat, lat_where, "lognormal_scaled_mixture");
  p.lat_ms.normal_median_ms = positive(lat, "normal_median", lat_where);
  p.lat_ms.sigma = positive(lat, "sigma", lat_where);
  p.lat_ms.degraded_factor = number_in(lat, "degraded_factor", lat_where, 1.0, kInf, false, true);

  const std::string jitter_where = where + "/jitter_ms";
  const json& jitter = common::require_object(object, "jitter_ms", where);
  require_family(jitter, jitter_where, "proportional_lognormal");
  p.jitter_ms.ratio_to_lat = non_negative(jitter, "ratio_to_lat", jitter_where);
  p.jitter_ms.cv = non_negative(jitter, "cv", jitter_where);

  p.loss_pct = parse_lognormal_term(common::require_object(object, "loss_pct", where),
                                    where + "/loss_pct", 100.0);
  p.throughput_mbps = parse_lognormal_term(common::require_object(object, "throughput_mbps", where),
                                           where + "/throughput_mbps", kInf);
  if (!(p.throughput_mbps.normal_mean > 0.0 && p.throughput_mbps.degraded_mean > 0.0)) {
    throw InputError(where + "/throughput_mbps: means must be > 0");
  }

  const std::string edge_where = where + "/edge_load";
  const json& edge = common::require_object(object, "edge_load", where);
  require_family(edge, edge_where, "beta");
  p.edge_load.normal_mean = open_unit(edge, "normal_mean", edge_where);
  p.edge_load.degraded_mean = open_unit(edge, "degraded_mean", edge_where);
  p.edge_load.normal_concentration = positive(edge, "normal_concentration", edge_where);
  p.edge_load.degraded_concentration = positive(edge, "degraded_concentration", edge_where);
  return p;
}

nlohmann::ordered_json lognormal_json(const LognormalTerm& t) {
  return {{"family", "lognormal"}, {"normal_mean", t.normal_mean},
          {"degraded_mean", t.degraded_mean}, {"cv", t.cv}};
}

}  // namespace

double ProcessTiming::normal_dwell_mean_s(double degraded_share) const {
  if (degraded_share <= 0.0) return HUGE_VAL;
  return degraded_dwell_mean_s * (1.0 - degraded_share) / degraded_share;
}

SliceProfiles parse_slice_profiles(const json& document, const std::string& where) {
  SliceProfiles profiles;
  if (document.is_object() && document.contains("description")) {
    profiles.description = common::require_string(document, "description", where);
  }
  const json& process = common::require_object(document, "process", where);
  const std::string process_where = where + "/process";
  profiles.timing.redraw_mean_s = positive(process, "redraw_mean_s", process_where);
  profiles.timing.min_dwell_s = non_negative(process, "min_dwell_s", process_where);
  profiles.timing.degraded_dwell_mean_s =
      positive(process, "degraded_dwell_mean_s", process_where);
  if (!(profiles.timing.degraded_dwell_mean_s > profiles.timing.min_dwell_s)) {
    throw InputError(process_where + ": degraded_dwell_mean_s must exceed min_dwell_s");
  }

  const json& slices = common::require_object(document, "slices", where);
  for (auto it = slices.begin(); it != slices.end(); ++it) {
    try {
      parse_slice(it.key());
    } catch (const std::invalid_argument& e) {
      throw InputError(where + "/slices/" + it.key() + ": " + e.what());
    }
  }
  for (Slice slice : kAllSlices) {
    profiles.at(slice) = parse_slice(common::require_object(slices, to_string(slice), where + "/slices"),
                                     slice, where + "/slices/" + to_string(slice));
  }
  return profiles;
}

SliceProfiles load_slice_profiles(const std::filesystem::path& path) {
  return parse_slice_profiles(common::load_json_file(path, 1u << 20), path.string() + ": ");
}

const SliceProfiles& default_slice_profiles() {
  static const SliceProfiles profiles = parse_slice_profiles(
      json::parse(default_slice_profiles_json()), "slice_profiles.json (compiled in): ");
  return profiles;
}

nlohmann::ordered_json to_json(const SliceProfiles& profiles) {
  nlohmann::ordered_json slices = nlohmann::ordered_json::object();
  for (const SliceProfile& p : profiles.slices) {
    slices[to_string(p.slice)] = {
        {"targets",
         {{"lat_ms",
           {{"mean", p.targets.lat_mean_ms},
            {"median", p.targets.lat_median_ms},
            {"p90", p.targets.lat_p90_ms}}},
          {"jitter_ms_mean", p.targets.jitter_mean_ms},
          {"loss_pct_mean", p.targets.loss_mean_pct},
          {"throughput_mbps_mean", p.targets.throughput_mean_mbps},
          {"edge_load_mean", p.targets.edge_load_mean}}},
        {"degraded_share", p.degraded_share},
        {"lat_ms",
         {{"family", "lognormal_scaled_mixture"},
          {"normal_median", p.lat_ms.normal_median_ms},
          {"sigma", p.lat_ms.sigma},
          {"degraded_factor", p.lat_ms.degraded_factor}}},
        {"jitter_ms",
         {{"family", "proportional_lognormal"},
          {"ratio_to_lat", p.jitter_ms.ratio_to_lat},
          {"cv", p.jitter_ms.cv}}},
        {"loss_pct", lognormal_json(p.loss_pct)},
        {"throughput_mbps", lognormal_json(p.throughput_mbps)},
        {"edge_load",
         {{"family", "beta"},
          {"normal_mean", p.edge_load.normal_mean},
          {"degraded_mean", p.edge_load.degraded_mean},
          {"normal_concentration", p.edge_load.normal_concentration},
          {"degraded_concentration", p.edge_load.degraded_concentration}}}};
  }
  nlohmann::ordered_json document = nlohmann::ordered_json::object();
  if (!profiles.description.empty()) document["description"] = profiles.description;
  document["process"] = {{"redraw_mean_s", profiles.timing.redraw_mean_s},
                         {"degraded_dwell_mean_s", profiles.timing.degraded_dwell_mean_s},
                         {"min_dwell_s", profiles.timing.min_dwell_s}};
  document["slices"] = slices;
  return document;
}

}  // namespace a3::linkemu
