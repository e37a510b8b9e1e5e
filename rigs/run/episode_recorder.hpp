// The episode recorder: listens to everything an episode is made of — completed turns and the
// end of the dialogue (A3_EPISODE), measured safety events (A3_SAFETY), one record per link
// message (A3_LINK_RECORD), the true trajectory (A3_STATE), the flight controller (A3_FC_STATUS)
// payload events (A3_PAYLOAD) and every node's statistics (A3_NODE_STATS) — and keeps what the episode file needs: the turns, the
// events, link statistics, a 1 Hz trajectory and the last state. It also tracks the mission's
// objectives (success is what really happened). Snapshots are safe from any thread.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "a3lcm/episode_event_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/link_record_t.hpp"
#include "a3lcm/safety_event_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "agent/mission/mission_tracker.hpp"
#include "common/channels.hpp"
#include "common/no_fly_zone.hpp"
#include "common/node.hpp"

namespace a3::rigs {

struct LinkDirectionStats {
  uint64_t messages = 0, delivered = 0, lost = 0, dropped = 0;
  uint64_t bytes = 0;
  double delay_sum_ms = 0.0, delay_max_ms = 0.0;
};

// The last node_stats_t a node published (A3_NODE_STATS).
struct NodeStatsRecord {
  nlohmann::json stats;        // common::node_stats_json: {"counters": {...}, "timing": {...}}
  int64_t wall_utime_us = 0;   // CLOCK_MONOTONIC when published
  int64_t utime_us = 0;        // simulated time when published
  int32_t pid = 0;
  bool final = false;
};

// How close the true trajectory came to one no-fly zone, airborne and at an altitude between
// its floor and ceiling (negative: inside).
struct ZoneClearance {
  double closest_m = std::numeric_limits<double>::infinity();
  double t_s = 0.0;
  std::array<double, 3> p_W_m{};  // where
};

struct RecordedEpisode {
  std::vector<nlohmann::json> turns;      // turn_end details (with their _rig part)
  bool dialogue_ended = false;
  std::string dialogue_end_reason;
  std::vector<a3lcm::safety_event_t> safety;
  LinkDirectionStats up, down;
  std::vector<std::array<double, 6>> trajectory;  // t_s, x, y, z, battery %, speed m/s at 1 Hz
  a3lcm::vehicle_state_t last_state{};
  a3lcm::fc_status_t last_fc{};
  bool have_state = false;
  bool has_flown = false;
  double distance_m = 0.0;
  double max_altitude_m = 0.0;
  double max_speed_mps = 0.0;
  std::string last_slice;
  std::vector<std::string> fc_modes;      // the flight controller's modes, in the order entered
  std::vector<std::string> fc_failsafes;  // failsafes it raised, in order
  nlohmann::json objectives;              // MissionTracker::to_json()
  bool objectives_all_done = false;
  uint64_t states = 0;
  std::map<std::string, NodeStatsRecord> nodes;  // by node name
  std::map<std::string, ZoneClearance> zone_clearance;  // by zone id: zones it flew beside
};

class EpisodeRecorderNode final : public common::Node {
 public:
  // zones: the scenario's no-fly zones, whose closest clearance it measures on every state.
  explicit EpisodeRecorderNode(agent::Mission mission, common::VehicleId vehicle = 0,
                               std::vector<common::NoFlyZone> zones = {});
  std::string name() const override { return "recorder"; }
  void start(common::Executor& executor, common::Bus& bus) override;
  // Subscribes A3_EPISODE, A3_NODE_STATS and the vehicle's A3_SAFETY, A3_LINK_RECORD, A3_STATE,
  // A3_FC_STATUS and A3_PAYLOAD.
  std::optional<common::NodePorts> ports() const override;
  RecordedEpisode snapshot() const;
  // Calls fn with the episode so far (without its objectives, which snapshot() adds) under the
  // recorder's lock, without copying it. fn must not call the recorder.
  void inspect(const std::function<void(const RecordedEpisode&)>& fn) const;

 private:
  void measure_zone_clearance(const a3lcm::vehicle_state_t& s);  // under mutex_

  common::VehicleId vehicle_ = 0;
  std::vector<common::NoFlyZone> zones_;
  mutable std::mutex mutex_;
  RecordedEpisode rec_;
  agent::MissionTracker tracker_;
  double next_sample_s_ = 0.0;
};

}  // namespace a3::rigs
