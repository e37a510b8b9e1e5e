// The simulated uav_swarm_agent: the scenario's other aircraft flying their planned paths, and
// its answers to collision_avoidance, swarm_status_check and swarm_formation, by rules on the
// rig's true state:
//   - collision_avoidance predicts, over horizon_s, the closest approach between our vehicle's
//     predicted path (SelfView::predicted: its legs timed at the ground speed it makes good in
//     the estimated wind, not the commanded speed) and each peer's plan (exactly: both are piecewise linear in time). A peer
//     is in conflict when that approach is closer than its min_separation_m + conflict_buffer_m.
//     With request "yield" or "pass" (the default), a conflicting peer that yields_when_asked
//     and has not yielded yet climbs yield_climb_m from now at yield_climb_rate_mps (its plan
//     changes, status "yielding") and the answer gives its new altitude and the predicted
//     separation after; a peer that does not yield (or already did) tells us to give way.
//     "query" only reports.
//   - swarm_status_check: each peer's position, heading (ENU degrees from east), speed,
//     status and distance to us.
//   - swarm_formation: a known formation (line, wedge, column, echelon, v) is accepted by the
//     peers within formation_radius_m of us that are not done or yielding, declined by the
//     others with the reason; the peers keep flying their own plans.
// Plan times are the run's clock in seconds (0 at the start of the run).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "a3lcm/traffic_state_t.hpp"
#include "vehicle/ground_shared.hpp"
#include "vehicle/peer_answer.hpp"

namespace a3::vehicle {

struct SwarmConfig {
  double horizon_s = 60.0;            // how far ahead closest approaches are predicted
  double conflict_buffer_m = 10.0;    // added to a peer's min separation to call a conflict
  // Our vehicle may run up to this late against its predicted path (the prediction ignores the
  // braking, settling and speeding up at each route waypoint — 8.6 s per waypoint measured at
  // 8 m/s in a 7 m/s tailwind, against the 3 s the energy model allows — and a headwind's gusts):
  // the closest approach is the nearest over every lateness in [0, own_lateness_s].
  double own_lateness_s = 15.0;
  double yield_climb_rate_mps = 2.5;  // how fast a yielding peer climbs
  // A yielding peer whose climb alone would pass closer than its separation + buffer also holds
  // its course (climbing in place) for as long as that takes, in 5 s steps up to this.
  double max_yield_hold_s = 60.0;
  double formation_radius_m = 300.0;  // peers farther than this decline a formation

  void validate(const std::string& where) const;
};

struct Approach {
  double distance_m = 0.0;
  double t_s = 0.0;  // when
  Eigen::Vector3d a_W_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d b_W_m = Eigen::Vector3d::Zero();
};

// The closest approach of two plans over [t0_s, t0_s + horizon_s] (exact).
Approach closest_approach(const TrafficPlan& a, const TrafficPlan& b, double t0_s, double horizon_s);
// The plan waiting where it is at t0 for delay_s, then flying the rest of its path that long later.
TrafficPlan delayed_plan(const TrafficPlan& plan, double t0, double delay_s);
// The closest approach when plan `late` may run up to max_late_s behind its times (sampled each
// second, the nearest kept; it waits where it is at t0 meanwhile).
Approach closest_approach_running_late(const TrafficPlan& late, const TrafficPlan& other, double t0, double horizon,
                                       double max_late_s);
// The plan climbing climb_m from t0_s at rate_mps on top of its course.
TrafficPlan climbed_plan(const TrafficPlan& plan, double t0_s, double climb_m, double rate_mps);

struct SwarmPeerState {
  TrafficPlan plan;
  bool yielded = false;
};

class SwarmPeer {
 public:
  // Throws std::invalid_argument naming the plan and field ("traffic[1].path: times must increase").
  SwarmPeer(std::vector<TrafficPlan> traffic, SwarmConfig config);

  PeerAnswer collision_avoidance(const SelfView& self, const nlohmann::json& payload);
  PeerAnswer swarm_status_check(const SelfView& self) const;
  PeerAnswer swarm_formation(const SelfView& self, const nlohmann::json& payload) const;

  std::vector<a3lcm::traffic_state_t> traffic_at(double t_s, int64_t utime_us) const;
  const std::vector<SwarmPeerState>& peers() const { return peers_; }
  std::string status_of(const SwarmPeerState& peer, double t_s) const;

 private:
  static constexpr double kYieldHoldStep_s = 5.0;
  struct YieldPlan {
    TrafficPlan plan;    // the peer's path, climbing (and holding) away
    Approach after;      // its closest approach to ours then
    double hold_s = 0.0; // how long it holds its course
  };
  // How `peer` yields to `ours` from `now` so as to pass at least wanted_m away, if it can.
  YieldPlan plan_yield(const TrafficPlan& ours, const TrafficPlan& peer, double now, double wanted_m) const;

  std::vector<SwarmPeerState> peers_;
  SwarmConfig config_;
};

}  // namespace a3::vehicle
