// Recorded network traces: a list of timed n_t vectors. Read from
//   - a JSON array of points {"t_s", "slice", "lat_ms", "jitter_ms", "loss_pct",
//     "throughput_mbps", "edge_load"[, "degraded"]}, with "t_s" on every point or on none
//     (then point i is at i · period_s);
//   - an object {"period_s"?, "trace": [points]};
//   - an α³-Bench episode file: the "net" vector of dialogue turn i at i · period_s.
// "degraded" defaults to the SPEC §2 hard test of the point.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "episode/episode.hpp"
#include "linkemu/network_state.hpp"

namespace a3::linkemu {

struct TracePoint {
  int64_t t_us = 0;  // from the start of the replay
  NetworkState state;
};

struct NetworkTrace {
  std::vector<TracePoint> points;  // strictly increasing t_us, at least one
  // The last point holds this long before a looping replay starts over.
  int64_t last_hold_us = 0;
  std::string source;  // file name or description, for logs
  int64_t duration_us() const { return points.back().t_us + last_hold_us; }
};

inline constexpr double kDefaultTracePeriodS = 5.0;

// period_s: spacing of points without "t_s" (and the hold of the last point); a "period_s"
// in the document wins. Throws common::InputError naming `where`, the point and the field.
NetworkTrace parse_network_trace(const nlohmann::json& document, const std::string& where,
                                 double period_s = kDefaultTracePeriodS);
// The "net" vector of each dialogue turn of an episode, turn i at i · period_s.
NetworkTrace episode_network_trace(const episode::Episode& episode, double period_s = kDefaultTracePeriodS);
NetworkTrace load_network_trace(const std::filesystem::path& path,
                                double period_s = kDefaultTracePeriodS);

nlohmann::json to_json(const NetworkTrace& trace);

}  // namespace a3::linkemu
