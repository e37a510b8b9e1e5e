// The steps every motion tool shares: the telemetry it needs before the gate can judge, the
// observation made from the fc's status for its command, and starting an onboard route.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <limits>
#include <vector>

#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "vehicle/onboard_route.hpp"
#include "vehicle/vehicle_services.hpp"

namespace a3::vehicle {

inline constexpr double kNoYaw = std::numeric_limits<double>::quiet_NaN();

// The fc's position and battery, or false after answering a gate refusal (no telemetry yet).
bool require_telemetry(VehicleServices& vehicle, Eigen::Vector3d* p_W_m, double* battery_pct);
// Answers from the fc's status for the command (nullptr: timed out): accepted (with extra),
// refused by the flight controller, or timeout; with the mode and pose.
void answer_motion(VehicleServices& vehicle, const a3lcm::fc_status_t* status, const nlohmann::json& accepted_extra);
// Starts the route (superseding any other), answers once the fc's status for its first leg
// comes; the route's speed becomes the cruise speed when the fc accepts.
void start_route(VehicleServices& vehicle, OnboardRoute route, nlohmann::json accepted_extra);

double route_length_m(const Eigen::Vector3d& start_W_m, const std::vector<Eigen::Vector3d>& points_W_m);
std::vector<Eigen::Vector3d> positions(const std::vector<RoutePoint>& points);

}  // namespace a3::vehicle
