// Go-to path following: along-track speed plus a capped PI cross-track correction.
#include "bridge/fc/path_following.hpp"

#include <algorithm>
#include <cmath>

namespace a3::bridge {

GotoPathFollower::GotoPathFollower(const FcParams& params) : params_(params) {}

void GotoPathFollower::start_leg(const Eigen::Vector2d& start_W_m, const Eigen::Vector2d& target_W_m,
                                 const Eigen::Vector2d& v_W_mps) {
  start_W_m_ = start_W_m;
  target_W_m_ = target_W_m;
  const Eigen::Vector2d leg = target_W_m - start_W_m;
  leg_length_m_ = leg.norm();
  along_W_ = leg_length_m_ > 0.0 ? Eigen::Vector2d(leg / leg_length_m_) : Eigen::Vector2d::UnitX();
  error_integral_m_s_ = 0.0;
  along_speed_sp_mps_ = v_W_mps.dot(along_W_);
}

bool GotoPathFollower::following() const {
  return params_.go_to.cross_track_p > 0.0 && leg_length_m_ >= kMinLegLength_m;
}

double GotoPathFollower::cross_track_error_m(const Eigen::Vector2d& p_W_m) const {
  const Eigen::Vector2d from_start = p_W_m - start_W_m_;
  return along_W_.x() * from_start.y() - along_W_.y() * from_start.x();
}

double GotoPathFollower::cross_track_correction_mps(double error_m, double limit_mps, double dt_s) {
  const FcGotoParams& g = params_.go_to;
  const double p_term = -g.cross_track_p * error_m;
  const double unclamped = p_term - g.cross_track_i * error_integral_m_s_;
  // Anti-windup: no integration that would push a saturated correction further.
  const bool saturated = std::abs(unclamped) >= limit_mps;
  const bool pushes_further = (unclamped > 0.0) == (error_m < 0.0);
  if (dt_s > 0.0 && g.cross_track_i > 0.0 && !(saturated && pushes_further)) {
    error_integral_m_s_ += error_m * dt_s;
    const double integral_limit_m_s = limit_mps / g.cross_track_i;
    error_integral_m_s_ = std::clamp(error_integral_m_s_, -integral_limit_m_s, integral_limit_m_s);
  }
  return std::clamp(p_term - g.cross_track_i * error_integral_m_s_, -limit_mps, limit_mps);
}

double GotoPathFollower::along_track_speed_mps(const Eigen::Vector2d& p_W_m, double limit_mps, double dt_s) {
  const double to_go_along_m = (target_W_m_ - p_W_m).dot(along_W_);
  const double wanted_mps = std::clamp(params_.gains.position_p * to_go_along_m, -limit_mps, limit_mps);
  const double step_mps = params_.go_to.along_track_accel_mps2 * dt_s;
  const double reachable_mps = std::abs(along_speed_sp_mps_) + step_mps;
  along_speed_sp_mps_ = std::clamp(wanted_mps, -reachable_mps, reachable_mps);
  return along_speed_sp_mps_;
}

Eigen::Vector2d GotoPathFollower::velocity_setpoint_mps(const Eigen::Vector2d& p_W_m, double speed_limit_mps,
                                                        double dt_s) {
  const double limit_mps = std::min(speed_limit_mps, params_.limits.max_horizontal_speed_mps);
  const double cross_limit_mps = std::min(params_.go_to.max_cross_track_speed_mps, limit_mps);
  const double cross_mps = cross_track_correction_mps(cross_track_error_m(p_W_m), cross_limit_mps, dt_s);
  const double along_limit_mps = std::sqrt(std::max(limit_mps * limit_mps - cross_mps * cross_mps, 0.0));
  const double along_mps = along_track_speed_mps(p_W_m, along_limit_mps, dt_s);
  const Eigen::Vector2d left_W(-along_W_.y(), along_W_.x());
  return along_mps * along_W_ + cross_mps * left_W;
}

}  // namespace a3::bridge
