// The flight controller's logic, independent of how sensors and commands reach it: modes
// (disarmed, takeoff, hold, go-to as path following, land, return-to-home following its line
// home, emergency), command checks, failsafes (command-link loss: hold, then return; low
// battery: return, then land; geofence and altitude envelope: refuse targets outside, brake
// before an edge, return if pushed outside), and the cascaded control loops down to four rotor
// throttles. The fc node wires it to CAN.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>

#include "bridge/fc/attitude_control.hpp"
#include "bridge/fc/fc_params.hpp"
#include "bridge/fc/path_following.hpp"
#include "bridge/fc/position_control.hpp"
#include "bridge/fc/state_estimator.hpp"

namespace a3::bridge {

// Values match lcmtypes/fc_status_t.lcm and fc_command_t.lcm.
enum class FcMode : int8_t { kDisarmed = 0, kTakeoff = 1, kHold = 2, kGoto = 3, kLand = 4, kReturnHome = 5, kEmergency = 6 };
enum class FcFailsafe : int8_t { kNone = 0, kLinkLoss = 1, kLowBattery = 2, kGeofence = 3, kAltitude = 4 };
enum class FlightCommandKind : int8_t {
  kHeartbeat = 0, kArm = 1, kDisarm = 2, kTakeoff = 3, kHold = 4, kGoto = 5, kLand = 6,
  kReturnHome = 7, kEmergencyStop = 8, kSetSpeed = 9
};
// Why a command was refused: the codes of a3.fc.Status.last_command_reason on CAN
// (bridge/dronecan/msg/a3_fc.hpp), so the fc node sends them as they are.
enum class FcRefusal : uint8_t {
  kNone = 0, kUnknownCommand = 1, kBadValue = 2, kNotArmed = 3, kInFlight = 4, kOnGround = 5,
  kOutsideGeofence = 6, kAboveAltitudeLimit = 7, kBelowAltitudeLimit = 8, kNoPositionFix = 9,
  kLowBattery = 10, kFailsafeActive = 11, kEmergencyStopped = 12, kBusy = 13
};
const char* to_string(FcMode mode);
const char* to_string(FcFailsafe failsafe);
const char* to_string(FcRefusal refusal);

struct FlightCommand {
  FlightCommandKind kind = FlightCommandKind::kHeartbeat;
  int32_t seq = 0;
  Eigen::Vector3d target_W_m = Eigen::Vector3d::Zero();  // go-to target; takeoff altitude in z
  double speed_limit_mps = 0.0;                          // <= 0: keep the current speed
  double yaw_deg = std::numeric_limits<double>::quiet_NaN();  // heading (ENU, from east); NaN: keep
};

struct FlightCommandResult {
  bool accepted = false;
  FcRefusal refusal = FcRefusal::kNone;
  std::string reason;  // empty when accepted
};

struct FlightStatus {
  FcMode mode = FcMode::kDisarmed;
  bool armed = false;
  FcFailsafe failsafe = FcFailsafe::kNone;
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_W_mps = Eigen::Vector3d::Zero();
  double yaw_deg = 0.0;
  double battery_pct = 100.0;
  int32_t last_command_seq = -1;
  bool last_command_accepted = false;
  FcRefusal last_refusal = FcRefusal::kNone;
  std::string last_reason;
};

struct FcOutput {
  std::array<double, 4> throttle{};
  bool armed = false;
};

class FlightController {
 public:
  explicit FlightController(FcParams params, EstimatorNoise noise = {});

  StateEstimator& estimator() { return estimator_; }
  const FcParams& params() const { return params_; }
  void on_battery(double t_s, double percent);
  // Any command (a heartbeat too) keeps the command link alive.
  FlightCommandResult on_command(const FlightCommand& command, double t_s);
  // One control step at time t_s (call at the control rate).
  FcOutput step(double t_s);
  const FlightStatus& status() const { return status_; }
  const Eigen::Vector3d& home_W_m() const { return home_W_m_; }
  // The current (or last) line followed: a go-to's leg, or the return home's home-bound leg.
  const GotoPathFollower& goto_path() const { return path_; }

 private:
  FlightCommandResult refuse(const FlightCommand& c, FcRefusal why, const std::string& detail);
  FlightCommandResult accept(const FlightCommand& c);
  void enter(FcMode mode);
  void arm(const EstimatedState& e);
  void check_failsafes(double t_s, const EstimatedState& e);
  Eigen::Vector3d brake_before_fence(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_sp) const;
  // Takes away the velocity toward each no-fly zone at the vehicle's altitude beyond what the
  // brake can stop before nfz_stop_margin_m outside it: the vehicle slides along the zone or
  // holds at its edge instead of entering. Pushed inside, it may only move out.
  Eigen::Vector3d brake_before_zones(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W,
                                     const Eigen::Vector3d& v_sp) const;
  std::string target_problem(const Eigen::Vector3d& target, FcRefusal* why) const;
  Eigen::Vector3d goto_leg_start(const EstimatedState& e) const;
  Eigen::Vector3d goto_velocity_setpoint(const Eigen::Vector3d& p_W, double speed_mps, double dt_s);
  Eigen::Vector3d return_home_velocity_setpoint(const EstimatedState& e, double dt_s);

  FcParams params_;
  StateEstimator estimator_;
  PositionController position_;
  GotoPathFollower path_;
  AttitudeController attitude_;
  FlightStatus status_;
  double last_step_t_s_ = -1.0;
  double last_command_t_s_ = 0.0;
  bool link_lost_ = false;
  Eigen::Vector3d home_W_m_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d hold_W_m_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d target_W_m_ = Eigen::Vector3d::Zero();
  double takeoff_altitude_m_ = 0.0;
  double yaw_sp_rad_ = 0.0;
  double speed_mps_ = 5.0;
  int return_phase_ = 0;
  Eigen::Vector3d return_start_W_m_ = Eigen::Vector3d::Zero();  // where the return home began
  double landed_since_s_ = -1.0;
  bool low_battery_returned_ = false;
};

}  // namespace a3::bridge
