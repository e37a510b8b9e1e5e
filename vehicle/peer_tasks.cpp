// The A2A tasks, each answered by its simulated peer: the swarm (collision_avoidance,
// swarm_status_check, swarm_formation), the weather service (request_weather_update) and the
// ground station (path_plan, handover_data: the handed-over images cross the downlink).
// collision_avoidance's answer also says what it assumed for our own track (own_track: its
// ground speed in the estimated wind) and the weather update gives the vehicle's own wind
// estimate beside the forecast (vehicle_wind).
#include "vehicle/vehicle_tools.hpp"
#include "vehicle/wind_reports.hpp"

namespace a3::vehicle {
namespace {

PeerAnswer collision_avoidance(VehicleServices& vehicle, const nlohmann::json& payload) {
  const SelfView self = vehicle.self_view();
  PeerAnswer answer = vehicle.swarm_peer().collision_avoidance(self, payload);
  if (self.known) {
    answer.payload["own_track"] =
        own_track_json(self, vehicle.gate().energy(), vehicle.wind_estimate(), vehicle.config().swarm.horizon_s);
  }
  return answer;
}

PeerAnswer swarm_status_check(VehicleServices& vehicle, const nlohmann::json&) {
  return vehicle.swarm_peer().swarm_status_check(vehicle.self_view());
}

PeerAnswer swarm_formation(VehicleServices& vehicle, const nlohmann::json& payload) {
  return vehicle.swarm_peer().swarm_formation(vehicle.self_view(), payload);
}

PeerAnswer request_weather_update(VehicleServices& vehicle, const nlohmann::json&) {
  PeerAnswer answer = vehicle.weather_service().weather_update(vehicle.self_view());
  if (answer.status == "ok") answer.payload["vehicle_wind"] = wind_report_json(vehicle.wind_estimate(), vehicle.now_s());
  return answer;
}

PeerAnswer path_plan(VehicleServices& vehicle, const nlohmann::json& payload) {
  return vehicle.ground_station().path_plan(vehicle.position(), payload);
}

PeerAnswer handover_data(VehicleServices& vehicle, const nlohmann::json& payload) {
  PeerAnswer answer = vehicle.ground_station().handover_data(vehicle.image_store(), payload);
  vehicle.count_image_bytes_downlinked(answer.extra_bytes);
  return answer;
}

}  // namespace

void add_peer_tasks(ToolHandlers& handlers) {
  handlers.add_task("collision_avoidance", collision_avoidance);
  handlers.add_task("swarm_status_check", swarm_status_check);
  handlers.add_task("swarm_formation", swarm_formation);
  handlers.add_task("request_weather_update", request_weather_update);
  handlers.add_task("path_plan", path_plan);
  handlers.add_task("handover_data", handover_data);
}

}  // namespace a3::vehicle
