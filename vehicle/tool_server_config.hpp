// Everything the vehicle-side tool server needs to know, built by the orchestrator from a
// scenario (and the airframe for the energy numbers). Positions are local ENU metres, times
// are the run's clock.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>

#include "common/channel.hpp"
#include "vehicle/energy_model.hpp"
#include "vehicle/ground_shared.hpp"
#include "vehicle/path_planner.hpp"
#include "vehicle/safety_gate.hpp"
#include "vehicle/sensor_suite.hpp"
#include "vehicle/swarm_peer.hpp"
#include "vehicle/weather_service.hpp"

namespace a3::vehicle {

struct RouteConfig {
  double arrive_tolerance_m = 2.0;     // HOLD this close to a waypoint counts as arrived
  double orbit_max_chord_m = 20.0;     // orbit circles are flown as chords at most this long
  std::size_t max_waypoints = 200;     // longest onboard route (navigate_to, orbit, survey)
  double default_survey_spacing_m = 20.0;

  void validate(const std::string& where) const;
};

struct ToolServerConfig {
  common::VehicleId vehicle = 0;  // whose channels (common/channel.hpp)
  // Geofence, altitude envelope, no-fly zones and peer traffic (initial_state.airspace plus
  // the scenario's extras).
  Airspace airspace;
  // The take-off point: where return_to_home goes and the battery estimate returns to.
  Eigen::Vector3d home_W_m = Eigen::Vector3d::Zero();
  // initial_state.env: weather, wind, gust (the weather service).
  WeatherEnv env;
  // initial_state.uav.sensors (name → health) and what uav.payloads declares (the sensor suite).
  SensorSuiteConfig sensors;
  EnergyModel energy;       // battery cost estimate (hover power, capacity, speeds, margin)
  AirframeLimits airframe;  // fc limits and drag: the ground speed made good in wind (ground_speed.hpp)
  GateConfig gate;          // margins, battery reserve, speed limit, return altitude
  ImageSizes images;        // bytes per image by sensor kind
  SwarmConfig swarm;        // collision-avoidance prediction and yielding
  WeatherConfig weather;    // gust factor and advisory thresholds
  PlannerConfig planner;    // path_plan clearance
  RouteConfig route;        // onboard route sequencing
  double fc_status_timeout_s = 2.0;    // wait for the fc's status of a command
  double slice_reply_timeout_s = 2.0;  // wait for the link emulator's slice-switch reply
  double traffic_rate_hz = 10.0;       // A3_TRAFFIC publication rate
  std::size_t max_queued_actions = 256;  // actions waiting beyond this are dropped and counted
  std::string sender = "tool_server";    // link_message_t.sender of observations, requester of slice switches

  // Throws std::invalid_argument naming the field ("ToolServerConfig.gate.nfz_margin_m must be ...").
  void validate() const;
};

}  // namespace a3::vehicle
