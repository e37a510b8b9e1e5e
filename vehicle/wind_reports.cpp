// The current leg's and the predicted own track's ground speeds in the estimated wind.
#include "vehicle/wind_reports.hpp"

#include <algorithm>
#include <cmath>

#include "vehicle/observation_json.hpp"

namespace a3::vehicle {
namespace {

nlohmann::json rounded_or_null(double x, int decimals) {
  if (!std::isfinite(x)) return nullptr;
  return rounded(x, decimals);
}

double course_deg(const Eigen::Vector2d& course_W) { return std::atan2(course_W.y(), course_W.x()) * 180.0 / M_PI; }

// The ground speed of the predicted leg a → b: as extrapolated (from the velocity) or as made good.
nlohmann::json predicted_leg_ground_speed(const SelfView& self, const TrafficWaypoint& a, const TrafficWaypoint& b,
                                          const EnergyModel& energy) {
  const Eigen::Vector2d course = b.p_W_m.head<2>() - a.p_W_m.head<2>();
  if (self.basis == TrackBasis::kVelocity) return rounded(self.v_W_mps.head<2>().norm());
  if (course.norm() < kMinCourse_m) return nullptr;
  return rounded(ground_speed_made_good_mps(energy, course, self.commanded_speed_mps));
}

}  // namespace

double ground_speed_made_good_mps(const EnergyModel& energy, const Eigen::Vector2d& course_W, double commanded_mps) {
  if (energy.ground_speed) return energy.ground_speed->ground_speed_mps(course_W, commanded_mps);
  return commanded_mps;
}

FlownLeg return_home_leg(const Eigen::Vector3d& p_W_m, const ToolServerConfig& config, double set_speed_mps,
                         const EnergyModel& energy) {
  FlownLeg leg;
  leg.kind = "return_home";
  leg.from_W_m = p_W_m;
  leg.points = return_home_legs(p_W_m, config.home_W_m, config.gate.return_altitude_m, config.airspace.min_altitude_m,
                                config.airspace.max_altitude_m);
  leg.commanded_speed_mps = std::max(set_speed_mps, energy.cruise_speed_mps);
  return leg;
}

nlohmann::json flown_leg_json(const FlownLeg& leg, const EnergyModel& energy, const Eigen::Vector2d& wind_W_mps) {
  const Eigen::Vector3d& end = leg.points.empty() ? leg.from_W_m : leg.points.back();
  const Eigen::Vector2d course = end.head<2>() - leg.from_W_m.head<2>();
  double eta_s = 0.0;
  Eigen::Vector3d from = leg.from_W_m;
  for (const auto& p : leg.points) {
    eta_s += energy.leg_time_s(from, p, leg.commanded_speed_mps);
    from = p;
  }
  nlohmann::json out = {{"kind", leg.kind},
                        {"target", point_json(end)},
                        {"distance_m", rounded(course.norm(), 1)},
                        {"course_deg", nullptr},
                        {"commanded_speed_mps", rounded(leg.commanded_speed_mps)},
                        {"ground_speed_mps", nullptr},
                        {"headwind_mps", nullptr},
                        {"crosswind_mps", nullptr},
                        {"eta_s", rounded_or_null(eta_s, 1)}};
  if (course.norm() < kMinCourse_m) return out;
  const Eigen::Vector2d u = course.normalized();
  out["course_deg"] = rounded(course_deg(u), 1);
  out["ground_speed_mps"] = rounded(ground_speed_made_good_mps(energy, u, leg.commanded_speed_mps));
  out["headwind_mps"] = rounded(-u.dot(wind_W_mps));
  out["crosswind_mps"] = rounded(u.x() * wind_W_mps.y() - u.y() * wind_W_mps.x());  // toward the course's left
  return out;
}

nlohmann::json own_track_json(const SelfView& self, const EnergyModel& energy, const WindEstimator& wind,
                              double horizon_s) {
  nlohmann::json legs = nlohmann::json::array();
  nlohmann::json first_ground_speed = nullptr;
  const auto& path = self.predicted.path;
  for (std::size_t i = 1; i < path.size() && path[i - 1].t_s < self.now_s + horizon_s; ++i) {
    nlohmann::json ground_speed = predicted_leg_ground_speed(self, path[i - 1], path[i], energy);
    if (first_ground_speed.is_null()) first_ground_speed = ground_speed;
    legs.push_back({{"to", point_array(path[i].p_W_m)},
                    {"arrive_in_s", rounded(path[i].t_s - self.now_s, 1)},
                    {"ground_speed_mps", std::move(ground_speed)}});
  }
  const bool extrapolated = self.basis == TrackBasis::kVelocity;
  return {{"basis", track_basis_name(self.basis)},
          {"commanded_speed_mps", extrapolated ? nlohmann::json(nullptr) : nlohmann::json(rounded(self.commanded_speed_mps))},
          {"ground_speed_mps", std::move(first_ground_speed)},
          {"wind", wind_report_json(wind, self.now_s)},
          {"legs", std::move(legs)}};
}

}  // namespace a3::vehicle
