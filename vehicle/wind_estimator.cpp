// The drag-balance wind estimate, low-passed, seeded by the forecast.
#include "vehicle/wind_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace a3::vehicle {
namespace {

constexpr double kGravity_mps2 = 9.80665;
constexpr double kMaxStepGap_s = 1.0;  // a longer gap between samples counts as this much

}  // namespace

Eigen::Vector2d wind_from_report(double speed_mps, double from_deg) {
  const double from = from_deg * M_PI / 180.0;
  return {-speed_mps * std::sin(from), -speed_mps * std::cos(from)};  // from north: moving south
}

double wind_from_deg(const Eigen::Vector2d& w) {
  if (w.norm() < 1e-9) return 0.0;
  const double deg = std::atan2(-w.x(), -w.y()) * 180.0 / M_PI;
  return deg < 0.0 ? deg + 360.0 : deg;
}

nlohmann::json wind_estimate_json(const WindEstimator& estimate) {
  const Eigen::Vector2d& w = estimate.wind_W_mps();
  return {{"speed_mps", std::round(w.norm() * 10.0) / 10.0},
          {"from_deg", std::round(wind_from_deg(w))},
          {"source", estimate.source()}};
}

nlohmann::json wind_report_json(const WindEstimator& estimate, double now_s) {
  nlohmann::json report = wind_estimate_json(estimate);
  report["learned_s"] = std::round(estimate.airborne_s() * 10.0) / 10.0;
  const auto updated_s = estimate.last_update_t_s();
  report["age_s"] = updated_s ? nlohmann::json(std::round(std::max(now_s - *updated_s, 0.0) * 10.0) / 10.0)
                              : nlohmann::json(nullptr);
  return report;
}

WindEstimator::WindEstimator(AirframeLimits limits, Eigen::Vector2d forecast_W_mps, double smoothing_s,
                             double settle_s)
    : limits_(limits), wind_W_mps_(std::move(forecast_W_mps)), smoothing_s_(smoothing_s), settle_s_(settle_s) {
  limits_.validate("airframe");
  if (!wind_W_mps_.allFinite()) throw std::invalid_argument("wind estimate: the forecast wind is not finite");
  if (!(smoothing_s_ > 0.0) || !(settle_s_ >= 0.0)) {
    throw std::invalid_argument("wind estimate: smoothing_s must be > 0 and settle_s >= 0");
  }
}

void WindEstimator::add(const WindSample& s) {
  const double dt = last_t_s_ < 0.0 ? 0.0 : std::min(s.t_s - last_t_s_, kMaxStepGap_s);
  if (dt < 0.0) return;
  last_t_s_ = s.t_s;
  if (s.on_ground || dt <= 0.0) return;
  const Eigen::Matrix3d R = s.q_WB.normalized().toRotationMatrix();
  const Eigen::Vector3d f_W = R * s.f_B_mps2;
  const Eigen::Vector3d a_W = f_W - Eigen::Vector3d(0.0, 0.0, kGravity_mps2);
  const Eigen::Vector3d z_B = R.col(2);
  if (a_W.norm() > max_accel_mps2 || z_B.z() < 0.5) return;  // not steady (or no accelerometer)
  const Eigen::Vector2d drag_N = limits_.mass_kg * (f_W.head<2>() - f_W.z() * z_B.head<2>() / z_B.z());
  Eigen::Vector2d air_W_mps = Eigen::Vector2d::Zero();
  if (drag_N.norm() > 1e-9) air_W_mps = -limits_.airspeed_for_drag_mps(drag_N.norm()) * drag_N.normalized();
  const Eigen::Vector2d measured = s.v_W_mps.head<2>() - air_W_mps;
  const double alpha = dt / (smoothing_s_ + dt);
  wind_W_mps_ += alpha * (measured - wind_W_mps_);
  airborne_s_ += dt;
  last_update_t_s_ = s.t_s;
}

}  // namespace a3::vehicle
