// The vehicle's estimate of the horizontal wind, for the ground-speed model (ground_speed.hpp).
// Seeded by the forecast (the scenario's env wind_mps and wind_dir_deg, the direction the wind
// blows FROM, degrees clockwise from north), then learned from the vehicle's state: in flight
// the rotors' thrust is along body z, so the horizontal force that is not thrust is drag,
//   D_h = m (f_W,h − f_W,z · z_B,h / z_B,z)   (f_W: the accelerometer's specific force in world,
//                                               z_B: body z in world; vertical drag neglected),
// and the drag's size gives the air speed (AirframeLimits::airspeed_for_drag_mps) against its
// direction, so wind = ground velocity − air velocity. Samples are low-passed with time
// constant smoothing_s (the Dryden gusts average out); once settle_s of airborne samples have
// been taken the estimate's source is "telemetry", before that it is the forecast's blend.
// Why the tilt balance and not ground velocity vs commanded velocity: the fc commands a ground
// velocity it often cannot reach in a headwind, so the shortfall says nothing of the wind's
// size; the drag balance holds in any steady flight, hover included.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "vehicle/ground_speed.hpp"

namespace a3::vehicle {

struct WindSample {
  double t_s = 0.0;
  Eigen::Vector3d v_W_mps = Eigen::Vector3d::Zero();   // ground velocity
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();
  Eigen::Vector3d f_B_mps2 = Eigen::Vector3d::Zero();  // specific force (accelerometer), body
  bool on_ground = true;
};

class WindEstimator {
 public:
  // forecast_W_mps: the forecast wind (ENU, the direction the air moves).
  WindEstimator(AirframeLimits limits, Eigen::Vector2d forecast_W_mps, double smoothing_s = 10.0,
                double settle_s = 5.0);

  // One state of the vehicle. Ignored on the ground, when accelerating harder than
  // max_accel_mps2 in any direction (not steady flight; a specific force of zero, no
  // accelerometer, reads as free fall) or when samples go back in time.
  void add(const WindSample& sample);

  const Eigen::Vector2d& wind_W_mps() const { return wind_W_mps_; }
  // "forecast" until settle_s of airborne samples, then "telemetry".
  std::string source() const { return airborne_s_ >= settle_s_ ? "telemetry" : "forecast"; }
  double airborne_s() const { return airborne_s_; }
  // When a state of the vehicle last moved the estimate (run's clock); none while it is the
  // forecast alone.
  std::optional<double> last_update_t_s() const { return last_update_t_s_; }

  double max_accel_mps2 = 1.5;  // steady enough for the drag balance

 private:
  AirframeLimits limits_;
  Eigen::Vector2d wind_W_mps_;
  double smoothing_s_;
  double settle_s_;
  double last_t_s_ = -1.0;
  double airborne_s_ = 0.0;
  std::optional<double> last_update_t_s_;
};

// The wind vector (ENU) for a report of speed and the direction it blows from (clockwise from
// north), and back: {speed, from_deg in [0, 360)}.
Eigen::Vector2d wind_from_report(double speed_mps, double from_deg);
double wind_from_deg(const Eigen::Vector2d& wind_W_mps);

// {"speed_mps", "from_deg", "source"}: the wind an ETA assumed, for observations.
nlohmann::json wind_estimate_json(const WindEstimator& estimate);
// The same plus how it was learned, for an agent reasoning about the wind: "learned_s" (seconds
// of steady flight behind the estimate) and "age_s" (since a state last moved it, at now_s;
// null while it is the forecast alone).
nlohmann::json wind_report_json(const WindEstimator& estimate, double now_s);

}  // namespace a3::vehicle
