// Flight-controller parameters from JSON.
#include "bridge/fc/fc_params.hpp"

#include "common/json_file.hpp"

namespace a3::bridge {
namespace {

using common::InputError;

void read(const nlohmann::json& o, const char* key, const std::string& where, double& field, bool positive) {
  field = common::number_or(o, key, field, where);
  if (positive ? !(field > 0.0) : field < 0.0) {
    throw InputError(where + "/" + key + ": must be " + (positive ? "> 0" : ">= 0") + ", got " +
                     std::to_string(field));
  }
}

const nlohmann::json* section(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.contains(key)) return nullptr;
  if (!j[key].is_object()) throw InputError(where + "/" + key + ": expected an object");
  return &j[key];
}

}  // namespace

FcParams fc_params_from_json(const nlohmann::json& j, const std::string& where, FcParams p) {
  if (!j.is_object()) throw InputError(where + ": flight-controller parameters must be a JSON object");
  if (const auto* v = section(j, "vehicle", where)) {
    const std::string w = where + "/vehicle";
    read(*v, "mass_kg", w, p.vehicle.mass_kg, true);
    read(*v, "arm_length_m", w, p.vehicle.arm_length_m, true);
    read(*v, "thrust_coeff_N_per_radps2", w, p.vehicle.thrust_coeff_N_per_radps2, true);
    read(*v, "torque_coeff_Nm_per_radps2", w, p.vehicle.torque_coeff_Nm_per_radps2, true);
    read(*v, "max_rotor_speed_radps", w, p.vehicle.max_rotor_speed_radps, true);
    read(*v, "inertia_xx_kgm2", w, p.vehicle.inertia_xx_kgm2, true);
    read(*v, "inertia_yy_kgm2", w, p.vehicle.inertia_yy_kgm2, true);
    read(*v, "inertia_zz_kgm2", w, p.vehicle.inertia_zz_kgm2, true);
  }
  if (const auto* g = section(j, "gains", where)) {
    const std::string w = where + "/gains";
    read(*g, "position_p", w, p.gains.position_p, true);
    read(*g, "velocity_p", w, p.gains.velocity_p, true);
    read(*g, "velocity_i", w, p.gains.velocity_i, false);
    read(*g, "attitude_p", w, p.gains.attitude_p, true);
    read(*g, "yaw_p", w, p.gains.yaw_p, true);
    read(*g, "rate_p", w, p.gains.rate_p, true);
    read(*g, "rate_i", w, p.gains.rate_i, false);
  }
  if (const auto* l = section(j, "limits", where)) {
    const std::string w = where + "/limits";
    read(*l, "max_horizontal_speed_mps", w, p.limits.max_horizontal_speed_mps, true);
    read(*l, "max_climb_speed_mps", w, p.limits.max_climb_speed_mps, true);
    read(*l, "max_descent_speed_mps", w, p.limits.max_descent_speed_mps, true);
    read(*l, "max_horizontal_accel_mps2", w, p.limits.max_horizontal_accel_mps2, true);
    read(*l, "max_tilt_deg", w, p.limits.max_tilt_deg, true);
    if (p.limits.max_tilt_deg >= 80.0) throw InputError(w + "/max_tilt_deg: must be below 80");
    read(*l, "max_rate_radps", w, p.limits.max_rate_radps, true);
    read(*l, "max_yaw_rate_radps", w, p.limits.max_yaw_rate_radps, true);
    read(*l, "takeoff_speed_mps", w, p.limits.takeoff_speed_mps, true);
    read(*l, "land_speed_mps", w, p.limits.land_speed_mps, true);
    read(*l, "brake_accel_mps2", w, p.limits.brake_accel_mps2, true);
    read(*l, "default_speed_mps", w, p.limits.default_speed_mps, true);
  }
  if (const auto* g = section(j, "goto", where)) {
    const std::string w = where + "/goto";
    read(*g, "cross_track_p", w, p.go_to.cross_track_p, false);
    read(*g, "cross_track_i", w, p.go_to.cross_track_i, false);
    read(*g, "max_cross_track_speed_mps", w, p.go_to.max_cross_track_speed_mps, true);
    read(*g, "along_track_accel_mps2", w, p.go_to.along_track_accel_mps2, true);
  }
  if (const auto* f = section(j, "failsafe", where)) {
    const std::string w = where + "/failsafe";
    read(*f, "link_loss_hold_s", w, p.failsafe.link_loss_hold_s, true);
    read(*f, "link_loss_return_s", w, p.failsafe.link_loss_return_s, false);
    read(*f, "low_battery_return_pct", w, p.failsafe.low_battery_return_pct, false);
    read(*f, "low_battery_land_pct", w, p.failsafe.low_battery_land_pct, false);
    read(*f, "fence_margin_m", w, p.failsafe.fence_margin_m, false);
    read(*f, "nfz_stop_margin_m", w, p.failsafe.nfz_stop_margin_m, false);
    read(*f, "return_altitude_m", w, p.failsafe.return_altitude_m, false);
    if (p.failsafe.low_battery_land_pct > p.failsafe.low_battery_return_pct) {
      throw InputError(w + ": low_battery_land_pct must not exceed low_battery_return_pct");
    }
  }
  read(j, "control_rate_hz", where, p.control_rate_hz, true);
  if (p.control_rate_hz < 200.0) {
    throw InputError(where + "/control_rate_hz: the ESC commands go out at the control rate, which must be >= 200 Hz");
  }
  read(j, "status_rate_hz", where, p.status_rate_hz, true);
  return p;
}

FcParams load_fc_params(const std::filesystem::path& path) {
  return fc_params_from_json(common::load_json_file(path), path.string());
}

}  // namespace a3::bridge
