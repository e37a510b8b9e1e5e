// The simulated swarm agent.
#include "vehicle/swarm_peer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "vehicle/observation_json.hpp"

namespace a3::vehicle {
namespace {

const std::set<std::string> kFormations = {"line", "wedge", "column", "echelon", "v"};

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

std::vector<double> breakpoints(const TrafficPlan& plan, double lo, double hi) {
  std::vector<double> out;
  for (const auto& w : plan.path) {
    if (w.t_s > lo && w.t_s < hi) out.push_back(w.t_s);
  }
  return out;
}

double heading_deg(const Eigen::Vector3d& v) {
  if (v.head<2>().norm() < 1e-6) return 0.0;
  return std::atan2(v.y(), v.x()) * 180.0 / M_PI;
}

std::string formation_list() {
  std::string out;
  for (const auto& f : kFormations) out += (out.empty() ? "" : ", ") + f;
  return out;
}

}  // namespace

void SwarmConfig::validate(const std::string& where) const {
  require(std::isfinite(horizon_s) && horizon_s > 0.0, where + ".horizon_s must be > 0, got " + std::to_string(horizon_s));
  require(std::isfinite(conflict_buffer_m) && conflict_buffer_m >= 0.0,
          where + ".conflict_buffer_m must be >= 0, got " + std::to_string(conflict_buffer_m));
  require(std::isfinite(own_lateness_s) && own_lateness_s >= 0.0 && own_lateness_s <= 600.0,
          where + ".own_lateness_s must be in [0, 600], got " + std::to_string(own_lateness_s));
  require(std::isfinite(max_yield_hold_s) && max_yield_hold_s >= 0.0 && max_yield_hold_s <= 600.0,
          where + ".max_yield_hold_s must be in [0, 600], got " + std::to_string(max_yield_hold_s));
  require(std::isfinite(yield_climb_rate_mps) && yield_climb_rate_mps > 0.0,
          where + ".yield_climb_rate_mps must be > 0, got " + std::to_string(yield_climb_rate_mps));
  require(std::isfinite(formation_radius_m) && formation_radius_m >= 0.0,
          where + ".formation_radius_m must be >= 0, got " + std::to_string(formation_radius_m));
}

Approach closest_approach(const TrafficPlan& a, const TrafficPlan& b, double t0, double horizon) {
  std::vector<double> times = {t0, t0 + horizon};
  for (double t : breakpoints(a, t0, t0 + horizon)) times.push_back(t);
  for (double t : breakpoints(b, t0, t0 + horizon)) times.push_back(t);
  std::sort(times.begin(), times.end());
  Approach best;
  best.distance_m = std::numeric_limits<double>::infinity();
  const auto consider = [&](double t) {
    const Eigen::Vector3d pa = a.position_at(t), pb = b.position_at(t);
    const double d = (pa - pb).norm();
    if (d < best.distance_m) best = {d, t, pa, pb};
  };
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    const double t1 = times[i], t2 = times[i + 1];
    consider(t1);
    if (t2 - t1 < 1e-9) continue;
    // Relative motion is linear on [t1, t2]: minimise |r1 + s (r2 - r1)| for s in [0, 1].
    const Eigen::Vector3d r1 = a.position_at(t1) - b.position_at(t1);
    const Eigen::Vector3d dr = (a.position_at(t2) - b.position_at(t2)) - r1;
    const double dd = dr.squaredNorm();
    if (dd > 1e-12) {
      const double s = std::clamp(-r1.dot(dr) / dd, 0.0, 1.0);
      consider(t1 + s * (t2 - t1));
    }
  }
  consider(times.back());
  return best;
}

TrafficPlan delayed_plan(const TrafficPlan& plan, double t0, double delay_s) {
  TrafficPlan delayed = plan;
  if (plan.path.empty() || !(delay_s > 0.0)) return delayed;
  const Eigen::Vector3d now_W_m = plan.position_at(t0);
  delayed.path.clear();
  delayed.path.push_back({t0, now_W_m});
  delayed.path.push_back({t0 + delay_s, now_W_m});  // waits, then flies the rest as planned
  for (const auto& w : plan.path) {
    if (w.t_s > t0 + 1e-9) delayed.path.push_back({w.t_s + delay_s, w.p_W_m});  // the past stays past
  }
  return delayed;
}

Approach closest_approach_running_late(const TrafficPlan& late, const TrafficPlan& other, double t0, double horizon,
                                       double max_late_s) {
  Approach best = closest_approach(late, other, t0, horizon);
  for (double delay_s = 1.0; delay_s <= max_late_s + 1e-9; delay_s += 1.0) {
    const Approach a = closest_approach(delayed_plan(late, t0, delay_s), other, t0, horizon);
    if (a.distance_m < best.distance_m) best = a;
  }
  return best;
}

TrafficPlan climbed_plan(const TrafficPlan& plan, double t0, double climb_m, double rate_mps) {
  const double t1 = t0 + climb_m / rate_mps;
  std::vector<double> times = {t0, t1};
  for (const auto& w : plan.path) times.push_back(w.t_s);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end(), [](double x, double y) { return std::abs(x - y) < 1e-9; }),
              times.end());
  TrafficPlan out = plan;
  out.path.clear();
  for (double t : times) {
    const double offset = std::clamp((t - t0) * rate_mps, 0.0, climb_m);
    out.path.push_back({t, plan.position_at(t) + Eigen::Vector3d(0.0, 0.0, offset)});
  }
  return out;
}

SwarmPeer::SwarmPeer(std::vector<TrafficPlan> traffic, SwarmConfig config) : config_(config) {
  config_.validate("swarm");
  std::set<std::string> ids;
  for (std::size_t i = 0; i < traffic.size(); ++i) {
    const auto& p = traffic[i];
    const std::string where = "traffic[" + std::to_string(i) + "]";
    require(!p.id.empty(), where + ".id must not be empty");
    require(ids.insert(p.id).second, where + ".id '" + p.id + "' is used twice");
    require(!p.path.empty(), where + ".path must have at least one point");
    for (std::size_t k = 0; k < p.path.size(); ++k) {
      require(std::isfinite(p.path[k].t_s) && p.path[k].p_W_m.allFinite(),
              where + ".path[" + std::to_string(k) + "] must be finite");
      require(k == 0 || p.path[k].t_s > p.path[k - 1].t_s, where + ".path[" + std::to_string(k) + "].t_s must increase");
    }
    require(std::isfinite(p.min_separation_m) && p.min_separation_m > 0.0, where + ".min_separation_m must be > 0");
    require(std::isfinite(p.yield_climb_m) && p.yield_climb_m >= 0.0, where + ".yield_climb_m must be >= 0");
    peers_.push_back({p, false});
  }
}

std::string SwarmPeer::status_of(const SwarmPeerState& peer, double t) const {
  const auto& path = peer.plan.path;
  if (path.size() > 1 && t >= path.back().t_s) return "done";
  if (peer.yielded) return "yielding";
  if (peer.plan.velocity_at(t).norm() < 1e-6) return "holding";
  return "en_route";
}

SwarmPeer::YieldPlan SwarmPeer::plan_yield(const TrafficPlan& ours, const TrafficPlan& peer, double now,
                                            double wanted_m) const {
  // Climb away; when the climb alone leaves less than the wanted separation, also hold the
  // course (climbing in place) a little longer each time, up to max_yield_hold_s. The first plan
  // that gives the wanted separation, else the one that gives the most (holding can bring the
  // peer closer: our vehicle may be flying toward where it would hold).
  YieldPlan best;
  best.after.distance_m = -1.0;
  for (double hold_s = 0.0; hold_s <= config_.max_yield_hold_s + 1e-9; hold_s += kYieldHoldStep_s) {
    YieldPlan y;
    y.hold_s = hold_s;
    y.plan = climbed_plan(delayed_plan(peer, now, hold_s), now, peer.yield_climb_m, config_.yield_climb_rate_mps);
    y.after = closest_approach_running_late(ours, y.plan, now, config_.horizon_s, config_.own_lateness_s);
    if (y.after.distance_m >= wanted_m) return y;
    if (y.after.distance_m > best.after.distance_m) best = std::move(y);
  }
  return best;
}

PeerAnswer SwarmPeer::collision_avoidance(const SelfView& self, const nlohmann::json& payload) {
  const std::string request = payload.value("request", std::string("yield"));
  PeerAnswer answer;
  if (!self.known) {
    answer.status = "failed";
    answer.payload = {{"error", "the swarm has no position for you yet"}};
    return answer;
  }
  const double now = self.now_s;
  nlohmann::json entries = nlohmann::json::array();
  int conflicts = 0, unresolved = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (auto& peer : peers_) {
    const Approach before =
        closest_approach_running_late(self.predicted, peer.plan, now, config_.horizon_s, config_.own_lateness_s);
    const double required = peer.plan.min_separation_m;
    const bool conflict = before.distance_m < required + config_.conflict_buffer_m;
    nearest = std::min(nearest, before.distance_m);
    nlohmann::json e = {{"id", peer.plan.id},
                        {"predicted_min_separation_m", rounded(before.distance_m, 1)},
                        {"time_to_closest_s", rounded(before.t_s - now, 1)},
                        {"required_separation_m", rounded(required, 1)},
                        {"conflict", conflict}};
    if (!conflict) {
      e["action"] = "none";
    } else {
      ++conflicts;
      if (request == "query") {
        e["action"] = "none";
        ++unresolved;
      } else if (peer.plan.yields_when_asked && !peer.yielded) {
        const YieldPlan yield = plan_yield(self.predicted, peer.plan, now, required + config_.conflict_buffer_m);
        peer.plan = yield.plan;
        peer.yielded = true;
        const Approach& after = yield.after;
        e["action"] = "yielding";
        e["climb_m"] = rounded(peer.plan.yield_climb_m, 1);
        e["climb_rate_mps"] = rounded(config_.yield_climb_rate_mps, 1);
        e["hold_s"] = rounded(yield.hold_s, 1);
        e["new_altitude_m"] = rounded(peer.plan.position_at(now + config_.horizon_s).z(), 1);
        e["predicted_separation_after_m"] = rounded(after.distance_m, 1);
        if (after.distance_m < required) ++unresolved;
      } else {
        e["action"] = peer.yielded ? "already_yielded" : "will_not_yield";
        e["advice"] = "give way: hold or change altitude until it has passed";
        ++unresolved;
      }
    }
    entries.push_back(std::move(e));
  }
  answer.payload = {{"request", request},
                    {"clear", conflicts == 0},
                    {"conflicts", conflicts},
                    {"horizon_s", rounded(config_.horizon_s, 1)},
                    {"peers", std::move(entries)},
                    {"recommendation", conflicts == 0    ? "proceed"
                                       : unresolved == 0 ? "proceed: the peers in conflict are yielding"
                                                         : "give_way: hold or change altitude"}};
  if (std::isfinite(nearest)) answer.payload["nearest_obstacle_m"] = rounded(nearest, 1);
  return answer;
}

PeerAnswer SwarmPeer::swarm_status_check(const SelfView& self) const {
  PeerAnswer answer;
  nlohmann::json list = nlohmann::json::array();
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& peer : peers_) {
    const Eigen::Vector3d p = peer.plan.position_at(self.now_s);
    const Eigen::Vector3d v = peer.plan.velocity_at(self.now_s);
    nlohmann::json e = {{"id", peer.plan.id},
                        {"pose", point_json(p)},
                        {"heading_deg", rounded(heading_deg(v), 1)},
                        {"speed_mps", rounded(v.norm(), 2)},
                        {"status", status_of(peer, self.now_s)}};
    if (self.known) {
      const double d = (p - self.p_W_m).norm();
      e["distance_m"] = rounded(d, 1);
      nearest = std::min(nearest, d);
    }
    list.push_back(std::move(e));
  }
  answer.payload = {{"count", peers_.size()}, {"peers", std::move(list)}};
  if (std::isfinite(nearest)) answer.payload["nearest_uav_m"] = rounded(nearest, 1);
  return answer;
}

PeerAnswer SwarmPeer::swarm_formation(const SelfView& self, const nlohmann::json& payload) const {
  PeerAnswer answer;
  const std::string formation = payload.value("formation", std::string("line"));
  const double spacing = payload.value("spacing_m", 20.0);
  if (kFormations.count(formation) == 0) {
    answer.status = "error";
    answer.payload = {{"error", "payload/formation: unknown formation '" + formation + "'; known: " + formation_list()}};
    return answer;
  }
  if (!(spacing > 0.0)) {
    answer.status = "error";
    answer.payload = {{"error", "payload/spacing_m: must be > 0"}};
    return answer;
  }
  nlohmann::json accepted = nlohmann::json::array(), declined = nlohmann::json::array();
  for (const auto& peer : peers_) {
    const std::string status = status_of(peer, self.now_s);
    const double d = self.known ? (peer.plan.position_at(self.now_s) - self.p_W_m).norm()
                                : std::numeric_limits<double>::infinity();
    if (status == "done" || status == "yielding") {
      declined.push_back({{"id", peer.plan.id}, {"reason", "it is " + status}});
    } else if (d > config_.formation_radius_m) {
      declined.push_back({{"id", peer.plan.id},
                          {"reason", self.known ? "too far: " + std::to_string(std::lround(d)) + " m > " +
                                                      std::to_string(std::lround(config_.formation_radius_m)) + " m"
                                                : "your position is unknown"}});
    } else {
      accepted.push_back(peer.plan.id);
    }
  }
  answer.payload = {{"formation", formation},
                    {"spacing_m", rounded(spacing, 1)},
                    {"leader", "requester"},
                    {"accepted", accepted},
                    {"declined", declined},
                    {"note", "the peers acknowledge the formation and keep flying their own plans"}};
  return answer;
}

std::vector<a3lcm::traffic_state_t> SwarmPeer::traffic_at(double t_s, int64_t utime_us) const {
  std::vector<a3lcm::traffic_state_t> out;
  for (const auto& peer : peers_) {
    a3lcm::traffic_state_t m{};
    m.utime_us = utime_us;
    m.id = peer.plan.id;
    const Eigen::Vector3d p = peer.plan.position_at(t_s), v = peer.plan.velocity_at(t_s);
    for (int k = 0; k < 3; ++k) {
      m.p_W_m[k] = p[k];
      m.v_W_mps[k] = v[k];
    }
    m.status = status_of(peer, t_s);
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace a3::vehicle
