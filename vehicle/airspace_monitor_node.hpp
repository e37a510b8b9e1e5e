// The airspace monitor: measures safety on the TRUE trajectory (A3_STATE) and the peers'
// positions (A3_TRAFFIC), and publishes safety_event_t on A3_SAFETY. The episode's safety
// flags come from these events. Rules (numbers from AirspaceMonitorConfig):
//   - nfz_intrusion: the vehicle is inside a no-fly zone (horizontally inside, between its
//     floor and ceiling); value = how deep inside, m.
//   - separation_breach: closer than a peer's min_separation_m (3-D; the peer's last reported
//     position carried forward at its velocity); value = the distance, m.
//   - geofence_exit: horizontally outside the geofence; value = how far outside, m.
//   - altitude_violation: above the envelope's maximum (always), or below its minimum while
//     airborne, unless near the take-off point (within takeoff_radius_m of where it last left
//     the ground: climbing out, landing at home) or in a vertical transit (|v_z| ≥
//     vertical_transit_speed_mps with horizontal speed ≤ vertical_transit_max_horizontal_mps:
//     a take-off climb or a landing descent anywhere). Hovering or flying below the minimum
//     away from the take-off point is a violation. value = the altitude, m.
//   - crash: the dynamics report a crash; value = the speed at the time, m/s.
// Each violation gives an event when it starts (detail "enter: ...") and one when it ends
// (detail "leave: ...", value = the worst of the episode: deepest, closest, highest/lowest);
// a violation ends only hysteresis_m back on the right side. counters() counts starts.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "a3lcm/safety_event_t.hpp"
#include "a3lcm/traffic_state_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/channels.hpp"
#include "common/node.hpp"
#include "vehicle/ground_shared.hpp"

namespace a3::vehicle {

struct AirspaceMonitorConfig {
  common::VehicleId vehicle = 0;            // whose A3_STATE it watches and A3_SAFETY it reports on
  Airspace airspace;                        // envelope, geofence, zones; traffic gives each peer's min separation
  double default_min_separation_m = 30.0;   // for peers on A3_TRAFFIC not in airspace.traffic
  double takeoff_radius_m = 15.0;           // below the minimum this close to the take-off point is allowed
  double vertical_transit_speed_mps = 0.2;
  double vertical_transit_max_horizontal_mps = 1.5;
  double airborne_altitude_m = 0.3;         // above this (and not on_ground) the vehicle is airborne
  double hysteresis_m = 0.5;
  double traffic_timeout_s = 1.0;           // a peer silent this long is no longer checked
  std::string source = "airspace_monitor";  // safety_event_t.source

  // Throws std::invalid_argument naming the field.
  void validate() const;
};


class AirspaceMonitorNode final : public common::Node {
 public:
  explicit AirspaceMonitorNode(AirspaceMonitorConfig config);

  std::string name() const override { return "airspace_monitor"; }
  // Subscribes A3_STATE and A3_TRAFFIC; publishes A3_SAFETY.
  std::optional<common::NodePorts> ports() const override {
    namespace ch = common::channels;
    return common::NodePorts()
        .subscribes(ch::kState.of(config_.vehicle))
        .subscribes(ch::kTraffic)
        .publishes(ch::kSafety.of(config_.vehicle));
  }
  void start(common::Executor& executor, common::Bus& bus) override;

  // nfz_intrusion, separation_breach, geofence_exit, altitude_violation, crash (violations
  // started), states (vehicle states checked). Safe from any thread.
  const common::CounterSet& counters() const override { return counter_set_; }
  // Safe from any thread.
  std::vector<a3lcm::safety_event_t> events() const;
  // The closest each peer came (m), over the whole run.
  std::map<std::string, double> closest_approach_m() const;

 private:
  struct Violation {
    bool active = false;
    double worst = 0.0;
    int64_t since_us = 0;
  };
  struct Peer {
    a3lcm::traffic_state_t last;
    double min_separation_m = 30.0;
    Violation breach;
  };

  void on_state(const a3lcm::vehicle_state_t& s);
  // The checks of one state: no-fly zones and geofence, the altitude envelope, separation.
  void check_zones_and_fence(const a3lcm::vehicle_state_t& s, const Eigen::Vector3d& p);
  void check_altitude(const a3lcm::vehicle_state_t& s, const Eigen::Vector3d& p, const Eigen::Vector3d& v);
  void check_separation(const a3lcm::vehicle_state_t& s, const Eigen::Vector3d& p);
  void on_traffic(const a3lcm::traffic_state_t& t);
  void publish(const a3lcm::vehicle_state_t& s, const std::string& kind, double value, const std::string& detail);
  // Starts or ends a violation; higher_is_worse says which way the value gets worse. what()
  // returns the violation's text, called only when an event is published (no text per state).
  template <typename WhatFn>
  void track(const a3lcm::vehicle_state_t& s, Violation& v, bool violating, bool cleared, std::string_view kind,
             double value, bool higher_is_worse, const WhatFn& what);

  AirspaceMonitorConfig config_;
  common::Bus* bus_ = nullptr;
  std::map<std::string, Peer> peers_;
  std::vector<Violation> zones_;
  Violation fence_, high_, low_;
  bool crashed_ = false;
  bool airborne_ = false;
  Eigen::Vector2d takeoff_xy_ = Eigen::Vector2d::Zero();
  bool have_takeoff_ = false;

  mutable std::mutex mutex_;
  common::CounterSet counter_set_;
  struct Counters {
    explicit Counters(common::CounterSet& s)
        : nfz_intrusion(s.add("nfz_intrusion")), separation_breach(s.add("separation_breach")),
          geofence_exit(s.add("geofence_exit")), altitude_violation(s.add("altitude_violation")),
          crash(s.add("crash")), states(s.add("states")) {}
    common::Counter &nfz_intrusion, &separation_breach, &geofence_exit, &altitude_violation, &crash, &states;
  } counts_{counter_set_};
  std::vector<a3lcm::safety_event_t> events_;
  std::map<std::string, double> closest_m_;
};

}  // namespace a3::vehicle
