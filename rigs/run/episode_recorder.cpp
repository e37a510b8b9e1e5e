// Recording an episode from the bus.
#include "rigs/run/episode_recorder.hpp"

#include <cmath>

#include "a3lcm/node_stats_t.hpp"
#include "a3lcm/payload_event_t.hpp"
#include "common/channels.hpp"
#include "common/json_text.hpp"
#include "common/node_stats.hpp"
#include "eval/json_shape.hpp"

namespace a3::rigs {

EpisodeRecorderNode::EpisodeRecorderNode(agent::Mission mission, common::VehicleId vehicle,
                                         std::vector<common::NoFlyZone> zones)
    : vehicle_(vehicle), zones_(std::move(zones)), tracker_(std::move(mission)) {}

void EpisodeRecorderNode::measure_zone_clearance(const a3lcm::vehicle_state_t& s) {
  if (s.on_ground) return;
  const Eigen::Vector2d xy(s.p_W_m[0], s.p_W_m[1]);
  for (const common::NoFlyZone& zone : zones_) {
    if (!zone.spans_altitude(s.p_W_m[2])) continue;
    const double clearance_m = zone.clearance_m(xy);
    ZoneClearance& c = rec_.zone_clearance[zone.id];
    if (clearance_m < c.closest_m) c = {clearance_m, s.utime_us * 1e-6, {s.p_W_m[0], s.p_W_m[1], s.p_W_m[2]}};
  }
}

std::optional<common::NodePorts> EpisodeRecorderNode::ports() const {
  namespace ch = common::channels;
  return common::NodePorts()
      .subscribes(ch::kEpisode)
      .listens(ch::kNodeStats)  // real time: the runtimes publish them
      .subscribes(ch::kSafety.of(vehicle_))
      .subscribes(ch::kLinkRecord.of(vehicle_))
      .subscribes(ch::kState.of(vehicle_))
      .subscribes(ch::kFcStatus.of(vehicle_))
      .subscribes(ch::kPayload.of(vehicle_));
}

RecordedEpisode EpisodeRecorderNode::snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  RecordedEpisode r = rec_;
  r.objectives = tracker_.to_json();
  r.objectives_all_done = tracker_.all_done();
  return r;
}

void EpisodeRecorderNode::inspect(const std::function<void(const RecordedEpisode&)>& fn) const {
  std::lock_guard<std::mutex> lock(mutex_);
  fn(rec_);
}

void EpisodeRecorderNode::start(common::Executor&, common::Bus& bus) {
  namespace ch = common::channels;
  bus.subscribe<a3lcm::episode_event_t>(ch::kEpisode, [this](const a3lcm::episode_event_t& e, int64_t) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (e.kind == "turn_end") {
      // A turn holds a reply's args (nested up to common/json_text's default) a few levels down.
      if (auto j = common::try_parse_json_text(e.detail_json, nullptr, eval::episode_json_limits())) rec_.turns.push_back(std::move(*j));
    } else if (e.kind == "dialogue_end") {
      rec_.dialogue_ended = true;
      const auto j = common::try_parse_json_text(e.detail_json).value_or(nlohmann::json());
      rec_.dialogue_end_reason = j.is_object() ? j.value("reason", "") : "";
    }
  });
  bus.subscribe<a3lcm::node_stats_t>(ch::kNodeStats, [this](const a3lcm::node_stats_t& m, int64_t) {
    std::lock_guard<std::mutex> lock(mutex_);
    NodeStatsRecord& n = rec_.nodes[m.node];
    if (n.final && !m.is_final) return;  // a late periodic report after the totals
    n = {common::node_stats_json(m), m.wall_utime_us, m.utime_us, m.pid, m.is_final != 0};
  });
  bus.subscribe<a3lcm::safety_event_t>(ch::kSafety.of(vehicle_), [this](const a3lcm::safety_event_t& e, int64_t) {
    std::lock_guard<std::mutex> lock(mutex_);
    rec_.safety.push_back(e);
  });
  bus.subscribe<a3lcm::link_record_t>(ch::kLinkRecord.of(vehicle_), [this](const a3lcm::link_record_t& r, int64_t) {
    std::lock_guard<std::mutex> lock(mutex_);
    LinkDirectionStats& d = r.direction == "up" ? rec_.up : rec_.down;
    ++d.messages;
    d.bytes += static_cast<uint64_t>(std::max<int64_t>(r.size_bytes, 0));
    if (r.outcome == a3lcm::link_record_t::DELIVERED) {
      ++d.delivered;
      const double delay_ms = (r.delivery_utime_us - r.utime_us) * 1e-3;
      d.delay_sum_ms += delay_ms;
      d.delay_max_ms = std::max(d.delay_max_ms, delay_ms);
    } else if (r.outcome == a3lcm::link_record_t::LOST) {
      ++d.lost;
    } else {
      ++d.dropped;
    }
    rec_.last_slice = r.slice;
  });
  bus.subscribe<a3lcm::vehicle_state_t>(ch::kState.of(vehicle_), [this](const a3lcm::vehicle_state_t& s, int64_t) {
    std::lock_guard<std::mutex> lock(mutex_);
    tracker_.on_state(s);
    const double t = s.utime_us * 1e-6;
    const double speed = std::sqrt(s.v_W_mps[0] * s.v_W_mps[0] + s.v_W_mps[1] * s.v_W_mps[1] + s.v_W_mps[2] * s.v_W_mps[2]);
    if (rec_.have_state) {
      rec_.distance_m += std::sqrt(std::pow(s.p_W_m[0] - rec_.last_state.p_W_m[0], 2) +
                                   std::pow(s.p_W_m[1] - rec_.last_state.p_W_m[1], 2) +
                                   std::pow(s.p_W_m[2] - rec_.last_state.p_W_m[2], 2));
    }
    rec_.max_altitude_m = std::max(rec_.max_altitude_m, s.p_W_m[2]);
    rec_.max_speed_mps = std::max(rec_.max_speed_mps, speed);
    if (!s.on_ground) rec_.has_flown = true;
    measure_zone_clearance(s);
    if (t >= next_sample_s_) {
      rec_.trajectory.push_back({t, s.p_W_m[0], s.p_W_m[1], s.p_W_m[2], s.battery_pct, speed});
      next_sample_s_ = std::floor(t) + 1.0;
    }
    rec_.last_state = s;
    rec_.have_state = true;
    ++rec_.states;
  });
  bus.subscribe<a3lcm::fc_status_t>(ch::kFcStatus.of(vehicle_), [this](const a3lcm::fc_status_t& s, int64_t) {
    std::lock_guard<std::mutex> lock(mutex_);
    tracker_.on_fc_status(s);
    static constexpr const char* kModes[] = {"disarmed", "takeoff", "hold", "goto", "land", "return_home", "emergency"};
    static constexpr const char* kFailsafes[] = {"none", "link_loss", "low_battery", "geofence", "altitude"};
    const std::string mode = s.mode >= 0 && s.mode <= 6 ? kModes[s.mode] : "unknown";
    if (rec_.fc_modes.empty() || rec_.fc_modes.back() != mode) rec_.fc_modes.push_back(mode);
    if (s.failsafe > 0 && s.failsafe <= 4 && s.failsafe != rec_.last_fc.failsafe) rec_.fc_failsafes.push_back(kFailsafes[s.failsafe]);
    rec_.last_fc = s;
  });
  bus.subscribe<a3lcm::payload_event_t>(ch::kPayload.of(vehicle_), [this](const a3lcm::payload_event_t& e, int64_t) {
    std::lock_guard<std::mutex> lock(mutex_);
    tracker_.on_payload(e);
  });
}

}  // namespace a3::rigs
