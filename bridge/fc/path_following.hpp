// Go-to as path following. A leg is the horizontal line from where the go-to started (the hold
// point, or the previous go-to's target when one was still in progress) to its target. The
// horizontal velocity setpoint is the along-track speed (P on the distance left along the line,
// capped at the speed limit: the same slow-down near the target as a point setpoint) plus a
// cross-track correction toward the line (P + I on the perpendicular error, capped at
// FcGotoParams::max_cross_track_speed_mps; the integral holds the line in steady wind, and it
// stops growing while the correction is saturated). The correction comes first: the along-track
// speed gets what the speed limit leaves, and it grows at most at along_track_accel_mps2 (it
// may drop at once), so that speeding up leaves acceleration for the correction. Altitude is not part of it (the caller keeps its
// vertical setpoint).
#pragma once

#include <Eigen/Core>

#include "bridge/fc/fc_params.hpp"

namespace a3::bridge {

class GotoPathFollower {
 public:
  // Legs shorter than this have no direction worth following: the go-to flies at the target.
  static constexpr double kMinLegLength_m = 1.0;

  explicit GotoPathFollower(const FcParams& params);

  // A new leg (horizontal, ENU metres), entered at velocity v_W_mps; resets the integral.
  void start_leg(const Eigen::Vector2d& start_W_m, const Eigen::Vector2d& target_W_m, const Eigen::Vector2d& v_W_mps);
  // False when path following is off (cross_track_p = 0) or the leg is too short.
  bool following() const;
  // Signed distance from the line, m: positive left of the direction of travel.
  double cross_track_error_m(const Eigen::Vector2d& p_W_m) const;
  // The horizontal velocity setpoint at p_W_m, norm ≤ speed_limit_mps; dt_s advances the integral.
  Eigen::Vector2d velocity_setpoint_mps(const Eigen::Vector2d& p_W_m, double speed_limit_mps, double dt_s);

  const Eigen::Vector2d& start_W_m() const { return start_W_m_; }
  const Eigen::Vector2d& target_W_m() const { return target_W_m_; }

 private:
  double cross_track_correction_mps(double error_m, double limit_mps, double dt_s);
  double along_track_speed_mps(const Eigen::Vector2d& p_W_m, double limit_mps, double dt_s);

  const FcParams& params_;
  Eigen::Vector2d start_W_m_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d target_W_m_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d along_W_ = Eigen::Vector2d::UnitX();  // unit vector from start to target
  double leg_length_m_ = 0.0;
  double error_integral_m_s_ = 0.0;
  double along_speed_sp_mps_ = 0.0;  // the last along-track speed setpoint
};

}  // namespace a3::bridge
