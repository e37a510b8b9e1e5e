// What the agent is told about the wind and what the vehicle makes good in it: the leg being
// flown (read_telemetry's "leg") and the own track that collision_avoidance predicted
// (its "own_track"), each with the ground speed of the energy model's ground-speed model in the
// estimated wind, so that an agent (or a reader of the episode) sees why an ETA or a predicted
// meeting is what it is.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "vehicle/energy_model.hpp"
#include "vehicle/peer_answer.hpp"
#include "vehicle/tool_server_config.hpp"
#include "vehicle/wind_estimator.hpp"

namespace a3::vehicle {

// A leg the vehicle is flying, from where it is (from_W_m) through points (the last is where
// the leg ends), its horizontal part commanded at commanded_speed_mps.
struct FlownLeg {
  std::string kind;  // "route": an onboard route's current waypoint; "return_home": the fc's return
  Eigen::Vector3d from_W_m = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> points;
  double commanded_speed_mps = 0.0;
};

// The fc's return home from p_W_m as it flies it (climb to the return altitude, fly home,
// descend: return_home_legs), commanded at the speed set last but at least the cruise speed.
FlownLeg return_home_leg(const Eigen::Vector3d& p_W_m, const ToolServerConfig& config, double set_speed_mps,
                         const EnergyModel& energy);

// Shorter horizontal moves have no course worth a ground speed (climbs, descents, arrivals).
constexpr double kMinCourse_m = 1.0;

// The ground speed made good along course_W (non-zero) at commanded_mps: the energy model's
// ground-speed model, or the commanded speed without one (calm air).
double ground_speed_made_good_mps(const EnergyModel& energy, const Eigen::Vector2d& course_W, double commanded_mps);

// {"kind", "target" (the leg's end), "distance_m" (horizontal), "course_deg" (ENU, from east),
//  "commanded_speed_mps", "ground_speed_mps", "headwind_mps" (the wind against the course;
//  negative: a tailwind), "crosswind_mps" (across it; positive from the right of the course,
//  pushing the vehicle left, negative from the left), "eta_s" (to the end, climbs and descents
//  included)}. The course, ground speed and wind components are null when the leg is (nearly)
//  vertical; eta_s is null when the wind does not let the vehicle make good the course.
nlohmann::json flown_leg_json(const FlownLeg& leg, const EnergyModel& energy, const Eigen::Vector2d& wind_W_mps);

// {"basis", "commanded_speed_mps" (null when extrapolated from the velocity), "ground_speed_mps"
//  (the first horizontal leg's; null when none), "wind" (wind_report_json), "legs": [{"to",
//  "arrive_in_s", "ground_speed_mps"}]}: the legs of self.predicted that start within horizon_s.
nlohmann::json own_track_json(const SelfView& self, const EnergyModel& energy, const WindEstimator& wind,
                              double horizon_s);

}  // namespace a3::vehicle
