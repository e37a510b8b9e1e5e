// The one airspace parser: the geofence and altitude envelope of the parsed initial_state plus
// a scenario's `airspace` extras (no-fly zones, other traffic) into the agent::Airspace that
// the tool server's safety gate, the airspace monitor and the agents' briefing all read (the
// fc's fence comes from the same InitialState: rigs/run/fc_setup.hpp).
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>

#include "agent/airspace.hpp"
#include "common/polygon.hpp"
#include "rigs/scenario/initial_state.hpp"

namespace a3::rigs {

// `where` names the value's JSON path ("file.json: /mission/objectives/0/point").
// Throws common::InputError naming it.
Eigen::Vector2d parse_point2(const nlohmann::json& j, const std::string& where);
Eigen::Vector3d parse_point3(const nlohmann::json& j, const std::string& where);
common::Polygon2d parse_polygon(const nlohmann::json& j, const std::string& where);

agent::NoFlyZone parse_no_fly_zone(const nlohmann::json& j, const std::string& where);
agent::TrafficPlan parse_traffic(const nlohmann::json& j, const std::string& where);

// The initial state's geofence and envelope, with the no-fly zones and traffic of `extras`
// (a scenario's top-level "airspace" object, or null). `where` names `extras`.
agent::Airspace parse_airspace(const InitialState& state, const nlohmann::json& extras, const std::string& where);

// What agents are told about the airspace: geofence, altitude envelope, no-fly zones, and
// the other aircraft (ids and declared intent, not their future).
nlohmann::json airspace_brief(const agent::Airspace& airspace);

}  // namespace a3::rigs
