// What the simulated peers know of our vehicle: its true position and velocity (A3_STATE, else
// the fc's estimate) and the path it is about to fly, predicted from what it was told to do:
// the onboard route's remaining waypoints at the ground speed it makes good at the route's
// speed in the estimated wind, climbing while it flies (EnergyModel::flown_leg_time_s), the take-off climb, the
// fc's return home or landing; holding still in HOLD or on the ground; straight on at its
// velocity when the fc flies somewhere the tool server did not send it.
#include <algorithm>
#include <cmath>

#include "vehicle/tool_server_node.hpp"
#include "vehicle/wind_reports.hpp"

namespace a3::vehicle {

SelfView ToolServerNode::self_view() const {
  SelfView view;
  view.now_s = executor_->clock().now_s();
  if (true_state_) {
    view.known = true;
    view.p_W_m = Eigen::Vector3d(true_state_->p_W_m[0], true_state_->p_W_m[1], true_state_->p_W_m[2]);
    view.v_W_mps = Eigen::Vector3d(true_state_->v_W_mps[0], true_state_->v_W_mps[1], true_state_->v_W_mps[2]);
  } else if (fc_status_) {
    view.known = true;
    view.p_W_m = *position();
    view.v_W_mps = Eigen::Vector3d(fc_status_->v_W_mps[0], fc_status_->v_W_mps[1], fc_status_->v_W_mps[2]);
  }
  view.predicted.id = "self";
  view.predicted.path.push_back({view.now_s, view.p_W_m});
  if (!view.known) return view;

  std::vector<Eigen::Vector3d> targets;
  view.commanded_speed_mps = speed_mps_;
  const int8_t mode = fc_status_ ? fc_status_->mode : static_cast<int8_t>(a3lcm::fc_status_t::HOLD);
  if (route_) {
    view.basis = TrackBasis::kRoute;
    targets = route_->remaining();
    view.commanded_speed_mps = route_->speed_mps();
  } else if (mode == a3lcm::fc_status_t::TAKEOFF && takeoff_target_W_m_) {
    view.basis = TrackBasis::kTakeoff;
    targets = {*takeoff_target_W_m_};
  } else if (mode == a3lcm::fc_status_t::RETURN_HOME) {
    view.basis = TrackBasis::kReturnHome;
    const FlownLeg home = return_home_leg(view.p_W_m, config_, speed_mps_, gate_.energy());
    targets = home.points;
    view.commanded_speed_mps = home.commanded_speed_mps;
  } else if (mode == a3lcm::fc_status_t::LAND) {
    view.basis = TrackBasis::kLand;
    targets = {Eigen::Vector3d(view.p_W_m.x(), view.p_W_m.y(), 0.0)};
  } else if (mode != a3lcm::fc_status_t::HOLD && mode != a3lcm::fc_status_t::DISARMED) {
    view.basis = TrackBasis::kVelocity;
    const double horizon_s = config_.swarm.horizon_s;
    view.predicted.path.push_back({view.now_s + horizon_s, view.p_W_m + view.v_W_mps * horizon_s});
    return view;
  }
  double t = view.now_s;
  Eigen::Vector3d from = view.p_W_m;
  for (const auto& target : targets) {
    // At the ground speed made good, climbing while flying as the fc does (a sum of climb and
    // cruise would predict the vehicle later than it comes, outside the lateness allowed).
    const double dt = gate_.energy().flown_leg_time_s(from, target, view.commanded_speed_mps);
    if (!std::isfinite(dt)) break;  // the wind holds the vehicle where it is
    if (dt <= 1e-6) continue;
    t += dt;
    view.predicted.path.push_back({t, target});
    from = target;
  }
  return view;
}

}  // namespace a3::vehicle
