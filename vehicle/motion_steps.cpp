// The steps every motion tool shares (motion_steps.hpp).
#include "vehicle/motion_steps.hpp"

#include <cstdio>

#include "vehicle/observation_json.hpp"

namespace a3::vehicle {

bool require_telemetry(VehicleServices& vehicle, Eigen::Vector3d* p_W_m, double* battery_pct) {
  const a3lcm::fc_status_t* status = vehicle.fc_status();
  if (status == nullptr) {
    vehicle.finish_gate_refusal("no telemetry from the flight controller yet: the vehicle's position is unknown");
    return false;
  }
  *p_W_m = *vehicle.position();
  *battery_pct = status->battery_pct;
  return true;
}

void answer_motion(VehicleServices& vehicle, const a3lcm::fc_status_t* s, const nlohmann::json& accepted_extra) {
  if (s == nullptr) {
    char text[128];
    std::snprintf(text, sizeof text, "no status from the flight controller within %.1f s",
                  vehicle.config().fc_status_timeout_s);
    vehicle.finish_mcp({{"status", "timeout"}, {"reason", text}, {"pose", vehicle.pose_now()}});
    return;
  }
  const Eigen::Vector3d p(s->p_W_m[0], s->p_W_m[1], s->p_W_m[2]);
  nlohmann::json result;
  if (s->last_command_accepted) {
    result = {{"status", "accepted"}};
  } else {
    result = refused_result(s->last_command_reason, "flight_controller");
  }
  result["mode"] = fc_mode_name(s->mode);
  result["pose"] = pose_json(p, s->yaw_deg);
  if (s->last_command_accepted) {
    for (const auto& [key, value] : accepted_extra.items()) result[key] = value;
  }
  vehicle.finish_mcp(result);
}

void start_route(VehicleServices& vehicle, OnboardRoute route, nlohmann::json accepted_extra) {
  const double speed = route.speed_mps();
  const int32_t seq = vehicle.begin_route(std::move(route));
  vehicle.await_status(seq, [&vehicle, extra = std::move(accepted_extra), speed](const a3lcm::fc_status_t* s) {
    if (s != nullptr && s->last_command_accepted) vehicle.set_speed_mps(speed);
    answer_motion(vehicle, s, extra);
  });
}

double route_length_m(const Eigen::Vector3d& start, const std::vector<Eigen::Vector3d>& points) {
  double length = 0.0;
  Eigen::Vector3d from = start;
  for (const auto& p : points) {
    length += (p - from).norm();
    from = p;
  }
  return length;
}

std::vector<Eigen::Vector3d> positions(const std::vector<RoutePoint>& points) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : points) out.push_back(p.p_W_m);
  return out;
}

}  // namespace a3::vehicle
