// Query tools: read_telemetry (the fc's estimate, the link's n_t, the wind estimate and what
// the vehicle makes good along its current leg) and check_geofence.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "common/text_format.hpp"
#include "vehicle/observation_json.hpp"
#include "vehicle/vehicle_tools.hpp"
#include "vehicle/wind_reports.hpp"

namespace a3::vehicle {
namespace {

const std::vector<std::string> kTelemetryFields = {"time_s", "pose",     "velocity", "speed_mps", "battery_pct", "mode",
                                                   "armed",  "failsafe", "link",     "route",     "wind",        "leg"};

nlohmann::json finite_or_null(double x, int decimals) {
  if (!std::isfinite(x)) return nullptr;
  return rounded(x, decimals);
}

std::string field_list() {
  std::string out;
  for (const auto& f : kTelemetryFields) out += (out.empty() ? "" : ", ") + f;
  return out;
}

nlohmann::json link_json(const a3lcm::network_state_t* net) {
  if (net == nullptr) return nullptr;
  nlohmann::json link = {{"slice", net->slice},
                         {"lat_ms", rounded(net->lat_ms, 2)},
                         {"jitter_ms", rounded(net->jitter_ms, 2)},
                         {"loss_pct", rounded(net->loss_pct, 3)},
                         {"throughput_mbps", rounded(net->throughput_mbps, 2)},
                         {"edge_load", rounded(net->edge_load, 3)},
                         {"degraded", net->degraded != 0}};
  if (!net->pending_slice.empty()) link["pending_slice"] = net->pending_slice;
  return link;
}

nlohmann::json route_json(const OnboardRoute* route) {
  if (route == nullptr) return nullptr;
  return {{"name", route->name()},
          {"waypoint", route->index() + 1},
          {"of", route->points().size()},
          {"target", point_json(route->current().p_W_m)}};
}

// The horizontal leg being flown from p: the fc's return home, else the onboard route's
// current waypoint; null when none (holding, taking off, landing, a go-to the server did not send).
nlohmann::json leg_json(VehicleServices& vehicle, const a3lcm::fc_status_t& s, const Eigen::Vector3d& p) {
  const EnergyModel& energy = vehicle.gate().energy();
  FlownLeg leg;
  if (s.mode == a3lcm::fc_status_t::RETURN_HOME) {
    leg = return_home_leg(p, vehicle.config(), vehicle.speed_mps(), energy);
  } else if (const OnboardRoute* route = vehicle.onboard_route()) {
    leg = {"route", p, {route->current().p_W_m}, route->speed_mps()};
  } else {
    return nullptr;
  }
  return flown_leg_json(leg, energy, vehicle.wind_estimate().wind_W_mps());
}

void read_telemetry(VehicleServices& vehicle, const nlohmann::json& args) {
  std::set<std::string> wanted;
  if (args.contains("fields")) {
    const auto& fields = args["fields"];
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const std::string f = fields[i].get<std::string>();
      if (std::find(kTelemetryFields.begin(), kTelemetryFields.end(), f) == kTelemetryFields.end()) {
        return vehicle.finish_error("args/fields/" + std::to_string(i) + ": unknown field '" + f +
                                    "'; the fields are: " + field_list());
      }
      wanted.insert(f);
    }
  }
  const a3lcm::fc_status_t* status = vehicle.fc_status();
  if (status == nullptr) {
    return vehicle.finish_mcp({{"status", "error"}, {"error", "no telemetry from the flight controller yet"}});
  }
  const auto& s = *status;
  const Eigen::Vector3d v(s.v_W_mps[0], s.v_W_mps[1], s.v_W_mps[2]);
  nlohmann::json result = {{"time_s", rounded(vehicle.now_s(), 2)},
                           {"pose", pose_json(*vehicle.position(), s.yaw_deg)},
                           {"velocity", {{"vx", rounded(v.x())}, {"vy", rounded(v.y())}, {"vz", rounded(v.z())}}},
                           {"speed_mps", rounded(v.norm())},
                           {"battery_pct", rounded(s.battery_pct, 1)},
                           {"mode", fc_mode_name(s.mode)},
                           {"armed", s.armed != 0},
                           {"failsafe", fc_failsafe_name(s.failsafe)},
                           {"link", link_json(vehicle.network_state())},
                           {"route", route_json(vehicle.onboard_route())},
                           {"wind", wind_report_json(vehicle.wind_estimate(), vehicle.now_s())},
                           {"leg", leg_json(vehicle, s, *vehicle.position())}};
  if (!wanted.empty()) {
    nlohmann::json picked = nlohmann::json::object();
    for (const auto& f : wanted) picked[f] = result[f];
    result = std::move(picked);
  }
  vehicle.finish_mcp(result);
}

// The no-fly zone nearest to p (horizontally), or null when there is none.
nlohmann::json nearest_zone_json(const Airspace& air, const Eigen::Vector3d& p) {
  const Eigen::Vector2d xy = p.head<2>();
  nlohmann::json nearest = nullptr;
  double nearest_d = std::numeric_limits<double>::infinity();
  for (const auto& z : air.no_fly_zones) {
    const double d = std::max(z.clearance_m(xy), 0.0);
    if (d < nearest_d) {
      nearest_d = d;
      const char* vertical = p.z() > z.ceiling_m ? "above" : p.z() < z.floor_m ? "below" : "within";
      nearest = {{"id", z.id}, {"distance_m", rounded(d, 1)}, {"vertical", vertical}};
    }
  }
  return nearest;
}

// Below this the vehicle's own position is on the ground, where the altitude envelope does not
// apply yet (the airspace monitor counts a vehicle airborne above 0.3 m).
constexpr double kOnGroundBelowM = 0.3;

void check_geofence(VehicleServices& vehicle, const nlohmann::json& args) {
  const auto here = vehicle.position();
  const bool all_given = args.contains("x") && args.contains("y") && args.contains("z");
  if (!here && !all_given) {
    return vehicle.finish_error("args: give x, y and z: the vehicle's position is not known yet");
  }
  const auto coord = [&](const char* key, int k) { return args.contains(key) ? args[key].get<double>() : (*here)[k]; };
  const Eigen::Vector3d p(coord("x", 0), coord("y", 1), coord("z", 2));
  const Airspace& air = vehicle.config().airspace;
  // The vehicle's own altitude on the ground (the pre-flight check): the envelope applies once
  // airborne, so the answer is about the column it takes off into, at the envelope's floor.
  const bool on_ground = !args.contains("z") && p.z() < kOnGroundBelowM;
  const Eigen::Vector3d judged(p.x(), p.y(), on_ground ? std::max(p.z(), air.min_altitude_m) : p.z());
  const Eigen::Vector2d xy = p.head<2>();
  const bool inside = air.inside_geofence(xy);
  const bool altitude_ok = air.altitude_ok(judged.z());
  const NoFlyZone* in_zone = air.zone_containing(judged);
  const std::string gate_reason = vehicle.gate().check_target(judged, "point");
  const char* status = in_zone != nullptr ? "in_no_fly_zone"
                       : !inside          ? "outside_geofence"
                       : !altitude_ok     ? "outside_altitude_envelope"
                                          : "inside_geofence";
  nlohmann::json result = {{"status", status},
                           {"point", point_json(p)},
                           {"inside_geofence", inside},
                           {"distance_to_boundary_m", finite_or_null(air.geofence_clearance_m(xy), 1)},
                           {"altitude_ok", altitude_ok},
                           {"alt_bounds", {finite_or_null(air.min_altitude_m, 1), finite_or_null(air.max_altitude_m, 1)}},
                           {"nfz_violation", in_zone != nullptr},
                           {"in_zone", in_zone != nullptr ? nlohmann::json(in_zone->id) : nlohmann::json(nullptr)},
                           {"nearest_nfz", nearest_zone_json(air, judged)},
                           {"flyable", gate_reason.empty()}};
  if (on_ground) {
    result["on_ground"] = true;
    result["note"] = "On the ground: the altitude envelope applies once airborne; judged for a take-off here, at " +
                     common::formatted("%.1f m", judged.z()) + ".";
  }
  if (!gate_reason.empty()) result["why_not_flyable"] = gate_reason;
  vehicle.finish_mcp(result);
}

}  // namespace

void add_query_tools(ToolHandlers& handlers) {
  handlers.add_tool("read_telemetry", read_telemetry);
  handlers.add_tool("check_geofence", check_geofence);
}

}  // namespace a3::vehicle
