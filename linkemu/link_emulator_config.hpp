// Everything the link emulator node can be told: seed, initial slice, regime timing
// overrides, handover delay, publish rate, link options (reordering, Gilbert–Elliott),
// edge model, input limits, trace replay, channel names. Readable from JSON (the "link"
// section of a rig configuration, or `a3rig node linkemu --config FILE`).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/channels.hpp"
#include "linkemu/edge_compute.hpp"
#include "linkemu/link_transmitter.hpp"
#include "linkemu/network_trace.hpp"
#include "linkemu/regime_process.hpp"
#include "linkemu/slice_profile.hpp"

namespace a3::linkemu {

struct LinkChannels {
  std::string up_tx = common::channels::kLinkUpTx.base;
  std::string up_rx = common::channels::kLinkUpRx.base;
  std::string down_tx = common::channels::kLinkDownTx.base;
  std::string down_rx = common::channels::kLinkDownRx.base;
  std::string net = common::channels::kNet.base;
  std::string record = common::channels::kLinkRecord.base;
  std::string edge_request = common::channels::kEdgeRequest.base;
  std::string edge_reply = common::channels::kEdgeReply.base;
  std::string slice_request = common::channels::kSliceRequest.base;
  std::string slice_reply = common::channels::kSliceReply.base;
  // Vehicle n's link (channel.hpp: vehicle 0's are the defaults above).
  static LinkChannels of_vehicle(common::VehicleId vehicle);
  // Every name with the same suffix appended (tests and benchmarks sharing a host).
  LinkChannels with_suffix(const std::string& suffix) const;
};

struct LinkEmulatorConfig {
  uint64_t seed = 1;
  Slice initial_slice = Slice::kEmbb;
  StartRegime start_regime = StartRegime::kStationary;
  // Overrides of the profiles' process timing. degraded_dwell_mean_s keeps every slice's
  // degraded share (the normal dwell follows); degraded_share changes it for every slice
  // (then the time averages no longer match SPEC §6 — a stress setting).
  std::optional<double> redraw_mean_s;
  std::optional<double> degraded_dwell_mean_s;
  std::optional<double> min_dwell_s;
  std::optional<double> degraded_share;

  double handover_delay_ms = 100.0;
  double net_rate_hz = 10.0;  // periodic A3_NET; 0: only when n_t changes
  LinkModelOptions link;
  EdgeComputeModel edge;

  int64_t max_message_bytes = int64_t{64} << 20;   // charged size per message
  int64_t max_pending_messages = 100000;           // per direction
  int64_t max_pending_bytes = int64_t{512} << 20;  // payload bytes held, per direction
  double max_backlog_s = 60.0;                     // transmitter backlog, per direction
  bool publish_records = true;                     // link_record_t on channels.record

  // Scripted outages: windows [start_us, end_us) of the run (from its start) in which every
  // slice is in its degraded regime. Ignored when a trace is replayed.
  struct Window {
    int64_t start_us = 0;
    int64_t end_us = 0;
  };
  std::vector<Window> forced_degradations;

  std::optional<NetworkTrace> trace;  // replay instead of the seeded process
  bool trace_loop = false;
  LinkChannels channels;
};

// Reads a config object; unknown keys are errors (they are usually typos). A "trace"
// {"path", "period_s", "loop"} is loaded, its path relative to base_dir.
// Throws common::InputError naming `where` and the key.
LinkEmulatorConfig parse_link_emulator_config(const nlohmann::json& object,
                                              const std::string& where,
                                              const std::filesystem::path& base_dir);
LinkEmulatorConfig load_link_emulator_config(const std::filesystem::path& path);

// Checks ranges; throws std::invalid_argument naming the field.
void validate(const LinkEmulatorConfig& config);

// The profiles with the config's timing and share overrides applied.
SliceProfiles effective_profiles(const SliceProfiles& profiles, const LinkEmulatorConfig& config);

StartRegime parse_start_regime(const std::string& text);
const char* to_string(StartRegime start);

}  // namespace a3::linkemu
