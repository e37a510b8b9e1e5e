// Mean wind and Dryden-type turbulence.
#include "dynamics/wind_field.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace a3::dynamics {
namespace {

constexpr double kFeetPerMetre = 3.28084;
constexpr std::size_t kKeptSamples = 12000;  // 10 min at 20 Hz: how far back queries may go

}  // namespace

Eigen::Vector3d wind_from_report(double speed_mps, double from_direction_deg) {
  const double from = from_direction_deg * M_PI / 180.0;
  // Blowing from north (0°) means moving south: -y in ENU.
  return {-speed_mps * std::sin(from), -speed_mps * std::cos(from), 0.0};
}

WindField::WindField(const Eigen::Vector3d& mean_W_mps, const TurbulenceParams& turbulence,
                     uint64_t seed)
    : mean_W_mps_(mean_W_mps),
      params_(turbulence),
      rng_(common::RngStreams(seed).stream("dynamics.turbulence")) {
  if (!(params_.sample_period_s > 0.0)) {
    throw std::invalid_argument("turbulence sample period must be > 0, got " +
                                std::to_string(params_.sample_period_s));
  }
  const Eigen::Vector3d horizontal(mean_W_mps.x(), mean_W_mps.y(), 0.0);
  const double speed = horizontal.norm();
  along_W_ = speed > 1e-9 ? Eigen::Vector3d(horizontal / speed) : Eigen::Vector3d::UnitX();
  across_W_ = Eigen::Vector3d::UnitZ().cross(along_W_);
  if (params_.enabled && speed > 0.0) {
    const double h_ft = std::clamp(params_.reference_altitude_m * kFeetPerMetre, 10.0, 1000.0);
    const double k = 0.177 + 0.000823 * h_ft;
    const double sigma_w = 0.1 * speed;
    const double sigma_uv = sigma_w / std::pow(k, 0.4);
    const double l_w_m = h_ft / kFeetPerMetre;
    const double l_uv_m = h_ft / std::pow(k, 1.2) / kFeetPerMetre;
    const double v = std::max(speed, 1.0);
    sigma_mps_ = {sigma_uv, sigma_uv, sigma_w};
    tau_s_ = {l_uv_m / v, l_uv_m / v, l_w_m / v};
  }
  // Start in the stationary distribution.
  samples_.push_back({sigma_mps_.x() * rng_.normal(), sigma_mps_.y() * rng_.normal(),
                      sigma_mps_.z() * rng_.normal()});
}

Eigen::Vector3d WindField::sample_gust(std::size_t k) {
  while (first_index_ + samples_.size() <= k) {
    const Eigen::Vector3d& last = samples_.back();
    Eigen::Vector3d next;
    for (int i = 0; i < 3; ++i) {
      // Exact discretisation of dx = -x/τ dt + σ √(2/τ) dW.
      const double decay = std::exp(-params_.sample_period_s / tau_s_[i]);
      next[i] = last[i] * decay + sigma_mps_[i] * std::sqrt(1.0 - decay * decay) * rng_.normal();
    }
    samples_.push_back(next);
    if (samples_.size() > kKeptSamples) {
      samples_.pop_front();
      ++first_index_;
    }
  }
  if (k < first_index_) {
    throw std::logic_error("wind queried " + std::to_string((first_index_ - k) * params_.sample_period_s) +
                           " s further back than kept");
  }
  return samples_[k - first_index_];
}

Eigen::Vector3d WindField::wind_W_mps(double t_s) {
  if (sigma_mps_.isZero()) return mean_W_mps_;
  const double x = std::max(t_s, 0.0) / params_.sample_period_s;
  const auto k = static_cast<std::size_t>(std::floor(x));
  const double frac = x - static_cast<double>(k);
  const Eigen::Vector3d gust = (1.0 - frac) * sample_gust(k) + frac * sample_gust(k + 1);
  return mean_W_mps_ + gust.x() * along_W_ + gust.y() * across_W_ + Eigen::Vector3d(0, 0, gust.z());
}

}  // namespace a3::dynamics
