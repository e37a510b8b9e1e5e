// α³-Bench initial_state → dynamics configuration.
#include "dynamics/scenario_setup.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "common/json_file.hpp"

namespace a3::dynamics {

const nlohmann::json& initial_state_of(const nlohmann::json& document, const std::string& where) {
  if (document.is_object() && document.contains("initial_state")) {
    return common::require_object(document, "initial_state", where);
  }
  if (!document.is_object()) throw common::InputError(where + ": expected a JSON object");
  return document;
}

void apply_initial_state(const nlohmann::json& state, const std::string& where, bool start_on_ground,
                         DynamicsNodeConfig& config) {
  const auto& env = common::require_object(state, "env", where);
  const double wind_mps = common::require_number(env, "wind_mps", where + "/env");
  const double wind_dir_deg = common::require_number(env, "wind_dir_deg", where + "/env");
  if (wind_mps < 0.0) throw common::InputError(where + "/env/wind_mps: must be >= 0");
  config.mean_wind_W_mps = wind_from_report(wind_mps, wind_dir_deg);

  const auto& uav = common::require_object(state, "uav", where);
  if (uav.contains("payloads")) {
    config.params = with_payloads(config.params, payloads_from_json(uav["payloads"], where + "/uav/payloads"));
  }
  const auto& pose = common::require_object(uav, "pose", where + "/uav");
  const std::string wp = where + "/uav/pose";
  const double z = common::require_number(pose, "z", wp);
  const double yaw_deg = common::number_or(pose, "yaw", 0.0, wp);
  VehicleState s;
  s.p_W_m = {common::require_number(pose, "x", wp), common::require_number(pose, "y", wp),
             start_on_ground ? 0.0 : z};
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  if (!start_on_ground && z > 0.0) {
    s.rotor_speed_radps.fill(QuadrotorModel(config.params).hover_speed_radps());
  }
  if (!start_on_ground) config.turbulence.reference_altitude_m = std::max(z, 3.0);
  config.initial_state = s;
}

}  // namespace a3::dynamics
