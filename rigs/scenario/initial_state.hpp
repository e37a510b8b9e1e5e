// The one parser of an α³-Bench initial_state (a scenario's, or any corpus episode's) into a
// typed InitialState that every component is configured from: the dynamics (pose, wind,
// payloads, battery), the flight controller's fence, the tool server (env, sensors, payloads)
// and the airspace (geofence, altitude envelopes). Sections owned by one component are parsed
// by that component's parser (env: vehicle::parse_weather_env; uav.sensors:
// vehicle::parse_sensor_health); uav.payloads, read by both the dynamics and the tool server, by
// rigs/scenario/uav_payloads.hpp.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/polygon.hpp"
#include "dynamics/scenario_setup.hpp"
#include "dynamics/vehicle_params.hpp"
#include "vehicle/sensor_suite_config.hpp"
#include "vehicle/weather_config.hpp"

namespace a3::rigs {

struct AltitudeBounds {
  double min_m = 0.0;
  double max_m = 0.0;
};

struct InitialState {
  std::string domain = "uav";
  double time_s = 0.0;
  vehicle::WeatherEnv env;                      // env (parsed by vehicle::parse_weather_env)
  common::Polygon2d geofence;                 // airspace.geofence[0].points; empty: unbounded
  std::optional<AltitudeBounds> alt_bounds;   // airspace.alt_bounds
  std::optional<AltitudeBounds> policy_alt_bounds;  // policy.alt_bounds
  Eigen::Vector3d pose_W_m = Eigen::Vector3d::Zero();  // uav.pose x, y, z (ENU metres)
  double yaw_deg = 0.0;                       // uav.pose.yaw, degrees from east
  double speed_mps = 0.0;
  double battery_pct = 100.0;                 // uav.energy.battery_pct
  // uav.sensors (name → health) and the declared part of uav.payloads (ids, kinds, power).
  vehicle::SensorSuiteConfig sensors;
  std::vector<dynamics::Payload> payloads;    // uav.payloads: the physical part

  // The altitude envelope the vehicle must keep: airspace.alt_bounds narrowed by
  // policy.alt_bounds (either may be absent; both absent: unbounded).
  AltitudeBounds envelope() const {
    AltitudeBounds b{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    for (const auto& limit : {alt_bounds, policy_alt_bounds}) {
      if (!limit) continue;
      b.min_m = std::max(b.min_m, limit->min_m);
      b.max_m = std::min(b.max_m, limit->max_m);
    }
    return b;
  }
};

// Parses an initial_state object; `where` names the source ("file.json: /initial_state").
// Throws common::InputError naming the JSON path of a missing, mistyped or out-of-range field.
InitialState parse_initial_state(const nlohmann::json& state, const std::string& where);

// The initial_state object of a JSON document: the document itself, or its "initial_state"
// (an episode). Throws common::InputError naming `where`.
const nlohmann::json& initial_state_of(const nlohmann::json& document, const std::string& where);

// An episode or initial_state file, parsed (`a3rig node dynamics|fc --scenario`). Throws
// common::InputError naming the file and JSON path.
InitialState load_initial_state_file(const std::string& path);

// What the dynamics start from: pose, wind, payloads, battery.
dynamics::FlightStart flight_start(const InitialState& state);

}  // namespace a3::rigs
