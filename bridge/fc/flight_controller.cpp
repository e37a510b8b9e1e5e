// Flight modes, command checks, failsafes, and the control cascade.
#include "bridge/fc/flight_controller.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace a3::bridge {
namespace {

constexpr double kArrivedDistance_m = 0.5;
constexpr double kArrivedSpeed_mps = 0.3;
constexpr double kOnGroundAltitude_m = 0.3;
constexpr double kLandDetectAltitude_m = 2.0;     // the estimate may be off by this much at touchdown
constexpr double kLandDetectThrustShare = 0.75;   // of the hover thrust
constexpr double kVelocityResponse_s = 0.5;       // how long the velocity loop takes to follow a brake

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

double yaw_of(const Eigen::Quaterniond& q) {
  const Eigen::Matrix3d R = q.toRotationMatrix();
  return std::atan2(R(1, 0), R(0, 0));
}

}  // namespace

const char* to_string(FcMode m) {
  switch (m) {
    case FcMode::kDisarmed: return "disarmed";
    case FcMode::kTakeoff: return "takeoff";
    case FcMode::kHold: return "hold";
    case FcMode::kGoto: return "goto";
    case FcMode::kLand: return "land";
    case FcMode::kReturnHome: return "return_home";
    case FcMode::kEmergency: return "emergency";
  }
  return "unknown";
}

const char* to_string(FcFailsafe f) {
  switch (f) {
    case FcFailsafe::kNone: return "none";
    case FcFailsafe::kLinkLoss: return "link_loss";
    case FcFailsafe::kLowBattery: return "low_battery";
    case FcFailsafe::kGeofence: return "geofence";
    case FcFailsafe::kAltitude: return "altitude";
  }
  return "unknown";
}

const char* to_string(FcRefusal r) {
  switch (r) {
    case FcRefusal::kNone: return "";
    case FcRefusal::kUnknownCommand: return "unknown command";
    case FcRefusal::kBadValue: return "invalid argument";
    case FcRefusal::kNotArmed: return "not armed";
    case FcRefusal::kInFlight: return "not allowed in flight";
    case FcRefusal::kOnGround: return "not allowed on the ground";
    case FcRefusal::kOutsideGeofence: return "outside the geofence";
    case FcRefusal::kAboveAltitudeLimit: return "above the altitude limit";
    case FcRefusal::kBelowAltitudeLimit: return "below the altitude limit";
    case FcRefusal::kNoPositionFix: return "no position estimate";
    case FcRefusal::kLowBattery: return "battery too low";
    case FcRefusal::kFailsafeActive: return "a failsafe is active";
    case FcRefusal::kEmergencyStopped: return "emergency stopped";
    case FcRefusal::kBusy: return "not allowed in the current mode";
  }
  return "refused";
}

FlightController::FlightController(FcParams params, EstimatorNoise noise)
    : params_(std::move(params)),
      estimator_(noise),
      position_(params_),
      path_(params_),
      attitude_(params_),
      speed_mps_(params_.limits.default_speed_mps) {}

void FlightController::on_battery(double, double percent) { status_.battery_pct = percent; }

FlightCommandResult FlightController::refuse(const FlightCommand& c, FcRefusal why, const std::string& detail) {
  status_.last_command_seq = c.seq;
  status_.last_command_accepted = false;
  status_.last_refusal = why;
  std::string reason = to_string(why);
  if (!detail.empty()) {
    reason += ": ";
    reason += detail;
  }
  status_.last_reason = std::move(reason);
  return {false, why, status_.last_reason};
}

FlightCommandResult FlightController::accept(const FlightCommand& c) {
  status_.last_command_seq = c.seq;
  status_.last_command_accepted = true;
  status_.last_refusal = FcRefusal::kNone;
  status_.last_reason.clear();
  return {true, FcRefusal::kNone, ""};
}

void FlightController::enter(FcMode mode) {
  if (mode != status_.mode) {
    if (mode == FcMode::kReturnHome) {
      return_phase_ = 0;
      return_start_W_m_ = estimator_.state().p_W_m;
    }
    if (mode == FcMode::kLand) landed_since_s_ = -1.0;
  }
  status_.mode = mode;
  status_.armed = mode != FcMode::kDisarmed && mode != FcMode::kEmergency;
}

void FlightController::arm(const EstimatedState& e) {
  home_W_m_ = e.p_W_m;
  home_W_m_.z() = 0.0;
  hold_W_m_ = e.p_W_m;
  yaw_sp_rad_ = yaw_of(e.q_WB);
  position_.reset_integrator();
  attitude_.reset_integrator();
  status_.failsafe = FcFailsafe::kNone;
  low_battery_returned_ = false;
}

std::string FlightController::target_problem(const Eigen::Vector3d& t, FcRefusal* why) const {
  const Geofence& fence = params_.fence;
  char text[200];
  if (!fence.altitude_ok(t.z())) {
    *why = t.z() > fence.max_altitude_m() ? FcRefusal::kAboveAltitudeLimit : FcRefusal::kBelowAltitudeLimit;
    std::snprintf(text, sizeof text, "altitude %.1f m is outside [%.1f, %.1f] m", t.z(), fence.min_altitude_m(),
                  fence.max_altitude_m());
    return text;
  }
  const Eigen::Vector2d xy(t.x(), t.y());
  if (!fence.contains_xy(xy) || fence.distance_to_edge_m(xy) < params_.failsafe.fence_margin_m) {
    *why = FcRefusal::kOutsideGeofence;
    std::snprintf(text, sizeof text, "(%.1f, %.1f) m is not %.1f m inside the geofence", t.x(), t.y(),
                  params_.failsafe.fence_margin_m);
    return text;
  }
  return "";
}

// A go-to that replaces one in progress continues from its target (legs of a route chain);
// from hold it starts at the hold point; otherwise where the vehicle is.
Eigen::Vector3d FlightController::goto_leg_start(const EstimatedState& e) const {
  if (status_.mode == FcMode::kGoto) return target_W_m_;
  if (status_.mode == FcMode::kHold) return hold_W_m_;
  return e.p_W_m;
}

Eigen::Vector3d FlightController::goto_velocity_setpoint(const Eigen::Vector3d& p_W, double speed_mps, double dt_s) {
  Eigen::Vector3d v = position_.velocity_setpoint(p_W, target_W_m_, speed_mps);
  if (path_.following()) v.head<2>() = path_.velocity_setpoint_mps(p_W.head<2>(), speed_mps, dt_s);
  return v;
}

// Return home in three phases: climb (or keep altitude) over the point where it began, follow
// the line from that point home at that altitude (as a go-to does), then land.
Eigen::Vector3d FlightController::return_home_velocity_setpoint(const EstimatedState& e, double dt_s) {
  const double altitude = std::max(params_.failsafe.return_altitude_m, params_.fence.min_altitude_m());
  const double cruise_z = std::min(std::max(e.p_W_m.z(), altitude), params_.fence.max_altitude_m());
  const double speed_mps = std::max(speed_mps_, params_.limits.default_speed_mps);
  if (return_phase_ == 0) {
    const Eigen::Vector3d p_sp(return_start_W_m_.x(), return_start_W_m_.y(), cruise_z);
    const Eigen::Vector3d v_sp = position_.velocity_setpoint(e.p_W_m, p_sp, speed_mps);
    if (std::abs(e.p_W_m.z() - cruise_z) < 1.0) {
      return_phase_ = 1;
      target_W_m_ = Eigen::Vector3d(home_W_m_.x(), home_W_m_.y(), cruise_z);
      path_.start_leg(return_start_W_m_.head<2>(), home_W_m_.head<2>(), e.v_W_mps.head<2>());
    }
    return v_sp;
  }
  if (return_phase_ == 1) {
    const Eigen::Vector3d v_sp = goto_velocity_setpoint(e.p_W_m, speed_mps, dt_s);
    if ((e.p_W_m.head<2>() - target_W_m_.head<2>()).norm() < 1.0 && e.v_W_mps.head<2>().norm() < 0.5) {
      hold_W_m_ = target_W_m_;
      return_phase_ = 2;
    }
    return v_sp;
  }
  hold_W_m_.z() = e.p_W_m.z();
  enter(FcMode::kLand);
  landed_since_s_ = -1.0;
  return Eigen::Vector3d::Zero();
}

FlightCommandResult FlightController::on_command(const FlightCommand& c, double t_s) {
  last_command_t_s_ = t_s;
  if (link_lost_) {
    link_lost_ = false;
    if (status_.failsafe == FcFailsafe::kLinkLoss) status_.failsafe = FcFailsafe::kNone;
  }
  const EstimatedState& e = estimator_.state();
  const bool flying = status_.armed && status_.mode != FcMode::kDisarmed;
  if (status_.mode == FcMode::kEmergency && c.kind != FlightCommandKind::kHeartbeat &&
      c.kind != FlightCommandKind::kEmergencyStop) {
    const bool on_ground = e.p_W_m.z() < kOnGroundAltitude_m;
    const bool restart = c.kind == FlightCommandKind::kArm || c.kind == FlightCommandKind::kTakeoff ||
                         c.kind == FlightCommandKind::kDisarm;
    if (!(on_ground && restart)) return refuse(c, FcRefusal::kEmergencyStopped, "motors were cut");
    enter(FcMode::kDisarmed);
  }
  switch (c.kind) {
    case FlightCommandKind::kHeartbeat:
      return {true, FcRefusal::kNone, ""};  // not a command: the last command's result stands
    case FlightCommandKind::kEmergencyStop:
      enter(FcMode::kEmergency);
      return accept(c);
    case FlightCommandKind::kArm:
    case FlightCommandKind::kTakeoff: {
      if (!e.valid()) return refuse(c, FcRefusal::kNoPositionFix, "the estimator has no attitude or position yet");
      if (status_.battery_pct <= params_.failsafe.low_battery_return_pct) {
        return refuse(c, FcRefusal::kLowBattery, std::to_string(status_.battery_pct) + " %");
      }
      if (c.kind == FlightCommandKind::kArm) {
        if (flying) return accept(c);
        arm(e);
        enter(FcMode::kHold);
        hold_W_m_ = e.p_W_m;
        return accept(c);
      }
      if (!std::isfinite(c.target_W_m.z()) || c.target_W_m.z() <= 0.5) {
        return refuse(c, FcRefusal::kBadValue, "take-off altitude must be above 0.5 m");
      }
      if (!params_.fence.altitude_ok(c.target_W_m.z()) && c.target_W_m.z() > params_.fence.max_altitude_m()) {
        return refuse(c, FcRefusal::kAboveAltitudeLimit, "take-off altitude above " +
                                                          std::to_string(params_.fence.max_altitude_m()) + " m");
      }
      if (!flying) arm(e);
      takeoff_altitude_m_ = c.target_W_m.z();
      hold_W_m_ = Eigen::Vector3d(e.p_W_m.x(), e.p_W_m.y(), std::max(e.p_W_m.z(), 0.0));
      enter(FcMode::kTakeoff);
      return accept(c);
    }
    case FlightCommandKind::kDisarm:
      if (flying && e.p_W_m.z() > kOnGroundAltitude_m) return refuse(c, FcRefusal::kInFlight, "land first");
      enter(FcMode::kDisarmed);
      return accept(c);
    case FlightCommandKind::kHold:
      if (!flying) return refuse(c, FcRefusal::kNotArmed, "");
      hold_W_m_ = e.p_W_m;
      enter(FcMode::kHold);
      return accept(c);
    case FlightCommandKind::kGoto: {
      if (!flying) return refuse(c, FcRefusal::kNotArmed, "");
      if (!finite(c.target_W_m) || !std::isfinite(c.speed_limit_mps)) return refuse(c, FcRefusal::kBadValue, "target");
      FcRefusal why = FcRefusal::kNone;
      const std::string problem = target_problem(c.target_W_m, &why);
      if (!problem.empty()) return refuse(c, why, problem);
      if (c.speed_limit_mps > 0.0) speed_mps_ = std::min(c.speed_limit_mps, params_.limits.max_horizontal_speed_mps);
      if (std::isfinite(c.yaw_deg)) yaw_sp_rad_ = c.yaw_deg * M_PI / 180.0;
      path_.start_leg(goto_leg_start(e).head<2>(), c.target_W_m.head<2>(), e.v_W_mps.head<2>());
      target_W_m_ = c.target_W_m;
      enter(FcMode::kGoto);
      return accept(c);
    }
    case FlightCommandKind::kLand:
      if (!flying) return refuse(c, FcRefusal::kNotArmed, "");
      hold_W_m_ = e.p_W_m;
      enter(FcMode::kLand);
      return accept(c);
    case FlightCommandKind::kReturnHome:
      if (!flying) return refuse(c, FcRefusal::kNotArmed, "");
      enter(FcMode::kReturnHome);
      return accept(c);
    case FlightCommandKind::kSetSpeed:
      if (!std::isfinite(c.speed_limit_mps) || c.speed_limit_mps <= 0.0) {
        return refuse(c, FcRefusal::kBadValue, "speed must be > 0 m/s");
      }
      speed_mps_ = std::min(c.speed_limit_mps, params_.limits.max_horizontal_speed_mps);
      return accept(c);
  }
  return refuse(c, FcRefusal::kUnknownCommand, std::to_string(static_cast<int>(c.kind)));
}

void FlightController::check_failsafes(double t_s, const EstimatedState& e) {
  const bool flying = status_.armed && e.p_W_m.z() > kOnGroundAltitude_m;
  if (!flying) return;
  const FcFailsafeParams& f = params_.failsafe;
  // Command link.
  const double silent_s = t_s - last_command_t_s_;
  if (silent_s > f.link_loss_hold_s && status_.mode != FcMode::kLand && status_.mode != FcMode::kReturnHome) {
    if (!link_lost_) {
      link_lost_ = true;
      status_.failsafe = FcFailsafe::kLinkLoss;
      hold_W_m_ = e.p_W_m;
      enter(FcMode::kHold);
    } else if (silent_s > f.link_loss_hold_s + f.link_loss_return_s) {
      enter(FcMode::kReturnHome);
    }
  }
  // Battery.
  if (status_.battery_pct <= f.low_battery_land_pct && status_.mode != FcMode::kLand) {
    status_.failsafe = FcFailsafe::kLowBattery;
    hold_W_m_ = e.p_W_m;
    enter(FcMode::kLand);
  } else if (status_.battery_pct <= f.low_battery_return_pct && !low_battery_returned_ &&
             status_.mode != FcMode::kLand && status_.mode != FcMode::kReturnHome) {
    low_battery_returned_ = true;
    status_.failsafe = FcFailsafe::kLowBattery;
    enter(FcMode::kReturnHome);
  }
  // Pushed outside the geofence (wind): go home.
  const Eigen::Vector2d xy(e.p_W_m.x(), e.p_W_m.y());
  if (!params_.fence.contains_xy(xy) && status_.mode != FcMode::kReturnHome && status_.mode != FcMode::kLand) {
    status_.failsafe = FcFailsafe::kGeofence;
    enter(FcMode::kReturnHome);
  }
  if (e.p_W_m.z() > params_.fence.max_altitude_m() && status_.failsafe == FcFailsafe::kNone) {
    status_.failsafe = FcFailsafe::kAltitude;
  }
}

Eigen::Vector3d FlightController::brake_before_fence(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_sp) const {
  const Geofence& fence = params_.fence;
  if (!fence.has_polygon()) return v_sp;
  const Eigen::Vector2d xy(p_W.x(), p_W.y());
  if (!fence.contains_xy(xy)) return v_sp;
  const double d = fence.distance_to_edge_m(xy) - 0.5 * params_.failsafe.fence_margin_m;
  const Eigen::Vector2d n = fence.outward_normal_near(xy);
  const double allowed = std::sqrt(2.0 * params_.limits.brake_accel_mps2 * std::max(d, 0.0));
  Eigen::Vector3d out = v_sp;
  const double toward = v_sp.x() * n.x() + v_sp.y() * n.y();
  if (toward > allowed) {
    out.x() -= (toward - allowed) * n.x();
    out.y() -= (toward - allowed) * n.y();
  }
  // Altitude envelope: never climb through the top.
  const double headroom = params_.fence.max_altitude_m() - p_W.z();
  out.z() = std::min(out.z(), std::sqrt(2.0 * params_.limits.brake_accel_mps2 * std::max(headroom, 0.0)));
  return out;
}

Eigen::Vector3d FlightController::brake_before_zones(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W,
                                                     const Eigen::Vector3d& v_sp) const {
  const double margin_m = params_.failsafe.nfz_stop_margin_m;
  const Eigen::Vector2d xy(p_W.x(), p_W.y());
  Eigen::Vector3d out = v_sp;
  for (const common::NoFlyZone& zone : params_.no_fly_zones) {
    if (!zone.spans_altitude(p_W.z(), margin_m)) continue;
    const double clearance_m = zone.clearance_m(xy);
    const Eigen::Vector2d away = zone.away_direction(xy);
    // The room left once the velocity loop has answered (it lags the setpoint by about
    // kVelocityResponse_s); beyond the stop point: back out, as a position loop would.
    const double moving_in_mps = std::max(-(v_W.x() * away.x() + v_W.y() * away.y()), 0.0);
    const double room_m = clearance_m - margin_m - moving_in_mps * kVelocityResponse_s;
    const double allowed = room_m >= 0.0 ? std::sqrt(2.0 * params_.limits.brake_accel_mps2 * room_m)
                                         : params_.gains.position_p * room_m;
    const double toward = -(out.x() * away.x() + out.y() * away.y());
    if (toward > allowed) {
      out.x() += (toward - allowed) * away.x();
      out.y() += (toward - allowed) * away.y();
    }
  }
  return out;
}

FcOutput FlightController::step(double t_s) {
  const double dt = last_step_t_s_ < 0.0 ? 0.0 : std::clamp(t_s - last_step_t_s_, 0.0, 0.05);
  last_step_t_s_ = t_s;
  const EstimatedState& e = estimator_.state();
  status_.p_W_m = e.p_W_m;
  status_.v_W_mps = e.v_W_mps;
  status_.yaw_deg = yaw_of(e.q_WB) * 180.0 / M_PI;
  FcOutput out;
  if (!status_.armed || !e.valid()) return out;

  check_failsafes(t_s, e);
  if (!status_.armed) return out;

  const FcLimits& l = params_.limits;
  Eigen::Vector3d v_sp = Eigen::Vector3d::Zero();
  bool integrate_xy = true;
  switch (status_.mode) {
    case FcMode::kTakeoff: {
      const double target = takeoff_altitude_m_;
      Eigen::Vector3d p_sp(hold_W_m_.x(), hold_W_m_.y(), target);
      v_sp = position_.velocity_setpoint(e.p_W_m, p_sp, l.max_horizontal_speed_mps);
      v_sp.z() = std::clamp(params_.gains.position_p * (target - e.p_W_m.z()), -l.max_descent_speed_mps,
                            l.takeoff_speed_mps);
      integrate_xy = e.p_W_m.z() > 1.0;  // no wind-up while the feet may still touch the ground
      if (std::abs(target - e.p_W_m.z()) < 0.3) {
        hold_W_m_ = p_sp;
        enter(FcMode::kHold);
      }
      break;
    }
    case FcMode::kHold:
      v_sp = position_.velocity_setpoint(e.p_W_m, hold_W_m_, speed_mps_);
      break;
    case FcMode::kGoto:
      v_sp = goto_velocity_setpoint(e.p_W_m, speed_mps_, dt);
      if ((e.p_W_m - target_W_m_).norm() < kArrivedDistance_m && e.v_W_mps.norm() < kArrivedSpeed_mps) {
        hold_W_m_ = target_W_m_;
        enter(FcMode::kHold);
      }
      break;
    case FcMode::kReturnHome:
      v_sp = return_home_velocity_setpoint(e, dt);
      break;
    case FcMode::kLand: {
      const Eigen::Vector3d p_sp(hold_W_m_.x(), hold_W_m_.y(), e.p_W_m.z());
      v_sp = position_.velocity_setpoint(e.p_W_m, p_sp, l.default_speed_mps);
      // Full descent speed down to 10 m, then the gentle landing speed.
      v_sp.z() = -std::clamp(0.3 * (e.p_W_m.z() - 10.0) + l.land_speed_mps, l.land_speed_mps, l.max_descent_speed_mps);
      integrate_xy = e.p_W_m.z() > 1.0;
      break;
    }
    case FcMode::kDisarmed:
    case FcMode::kEmergency:
      return out;
  }
  if (status_.mode != FcMode::kDisarmed && status_.mode != FcMode::kEmergency) {
    v_sp = brake_before_zones(e.p_W_m, e.v_W_mps, brake_before_fence(e.p_W_m, v_sp));
  }
  const ThrustSetpoint ts = position_.thrust(e.v_W_mps, v_sp, yaw_sp_rad_, dt, integrate_xy);
  if (status_.mode == FcMode::kLand) {
    // Land detection as autopilots do it: low over the ground estimate, no vertical motion
    // although it is asked to descend, and the thrust wound down well below hover (the ground
    // carries the weight) — for a second. The thrust test keeps an altitude error from
    // disarming it in the air.
    const double hover_thrust_N = params_.vehicle.mass_kg * 9.80665;
    const bool landed = e.p_W_m.z() < kLandDetectAltitude_m && std::abs(e.v_W_mps.z()) < 0.25 &&
                        ts.thrust_N < kLandDetectThrustShare * hover_thrust_N;
    if (landed) {
      if (landed_since_s_ < 0.0) landed_since_s_ = t_s;
      if (t_s - landed_since_s_ > 1.0) {
        enter(FcMode::kDisarmed);
        return out;
      }
    } else {
      landed_since_s_ = -1.0;
    }
  }
  const Eigen::Vector3d w_sp = attitude_.rate_setpoint(e.q_WB, ts.q_sp);
  // No rate integration while the feet may touch the ground (the ground holds the attitude).
  const Eigen::Vector3d torque = attitude_.torque(e.w_B_radps, w_sp, e.p_W_m.z() > 1.0 ? dt : 0.0);
  out.throttle = mix(params_.vehicle, ts.thrust_N, torque);
  out.armed = true;
  return out;
}

}  // namespace a3::bridge
