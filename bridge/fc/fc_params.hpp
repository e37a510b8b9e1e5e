// Flight-controller parameters: what the autopilot knows of its vehicle (for the mixer and the
// thrust model), control gains, limits and failsafe thresholds. Loaded from JSON; every field
// has a documented default (bridge/fc/README.md), the vehicle section defaults to the 3DR Iris.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "bridge/fc/geofence.hpp"
#include "common/no_fly_zone.hpp"

namespace a3::bridge {

struct FcVehicle {
  double mass_kg = 1.5;
  double arm_length_m = 0.255;
  double thrust_coeff_N_per_radps2 = 5.84e-6;
  double torque_coeff_Nm_per_radps2 = 3.504e-7;
  double max_rotor_speed_radps = 1100.0;
  double inertia_xx_kgm2 = 0.029125, inertia_yy_kgm2 = 0.029125, inertia_zz_kgm2 = 0.055225;
};

struct FcGains {
  double position_p = 0.9;        // 1/s: velocity setpoint per metre of position error
  double velocity_p = 2.5;        // 1/s: acceleration per m/s of velocity error
  double velocity_i = 0.6;        // 1/s²
  double attitude_p = 7.0;        // 1/s: body-rate setpoint per radian of attitude error
  double yaw_p = 2.5;             // 1/s
  double rate_p = 20.0;           // 1/s: angular acceleration per rad/s of rate error
  double rate_i = 4.0;            // 1/s²
};

struct FcLimits {
  double max_horizontal_speed_mps = 12.0;
  double max_climb_speed_mps = 3.0;
  double max_descent_speed_mps = 2.0;
  double max_horizontal_accel_mps2 = 4.0;
  double max_tilt_deg = 30.0;
  double max_rate_radps = 3.0;
  double max_yaw_rate_radps = 1.5;
  double takeoff_speed_mps = 2.0;
  double land_speed_mps = 0.7;
  double brake_accel_mps2 = 2.5;    // how hard it may brake before a geofence edge
  double default_speed_mps = 5.0;   // go-to speed when a command gives none
};

struct FcFailsafeParams {
  double link_loss_hold_s = 3.0;    // no command heartbeat this long: hold
  double link_loss_return_s = 10.0; // still none this much longer: return home
  double low_battery_return_pct = 25.0;
  double low_battery_land_pct = 12.0;
  double fence_margin_m = 5.0;      // targets must stay this far inside the geofence
  double nfz_stop_margin_m = 2.0;   // the brake stops this far outside a no-fly zone
  double return_altitude_m = 30.0;  // minimum altitude of the return leg
};

// Go-to as path following (path_following.hpp): the velocity setpoint's correction toward the
// line from the leg's start to its target. cross_track_p = 0 turns path following off: the
// go-to then points its velocity at the target, as before issue 15.
struct FcGotoParams {
  double cross_track_p = 1.0;              // 1/s: velocity toward the line per metre off it
  double cross_track_i = 0.25;             // 1/s²: per metre-second off it (steady wind)
  double max_cross_track_speed_mps = 3.0;  // cap of the correction (P + I), m/s
  double along_track_accel_mps2 = 2.0;     // how fast the along-track speed setpoint may grow
};

struct FcParams {
  FcVehicle vehicle;
  FcGains gains;
  FcLimits limits;
  FcGotoParams go_to;
  FcFailsafeParams failsafe;
  Geofence fence;               // from the scenario; unbounded by default
  std::vector<common::NoFlyZone> no_fly_zones;  // from the scenario: braked before, like the fence
  double control_rate_hz = 250.0;
  double status_rate_hz = 10.0;
};

// Reads the sections present in `j` over the defaults; `where` names the source in errors.
FcParams fc_params_from_json(const nlohmann::json& j, const std::string& where, FcParams base = {});
FcParams load_fc_params(const std::filesystem::path& path);

}  // namespace a3::bridge
