// Wind at the vehicle: the scenario's mean wind plus seeded turbulence.
//
// Turbulence is a Dryden-type model: each of the along-wind, cross-wind and vertical components
// is an exponentially correlated (first-order Gauss-Markov) process, the first-order form of
// the Dryden shaping filters, with the low-altitude intensities and scale lengths of
// MIL-F-8785C §3.7.2.3 / MIL-HDBK-1797 (σ_w = 0.1·W20, σ_u = σ_v = σ_w/(0.177+0.000823h)^0.4,
// L_w = h, L_u = L_v = h/(0.177+0.000823h)^1.2, h in ft, 10 ≤ h ≤ 1000 ft), correlation time
// L/V with V the mean wind speed (at least 1 m/s). The process is sampled on a fixed grid
// (20 Hz) from a named RNG stream and interpolated linearly, so the wind is a continuous
// function of time: an adaptive integrator may evaluate it anywhere, in any order, and a run
// is reproducible for a seed.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <deque>

#include "common/rng.hpp"

namespace a3::dynamics {

// The wind vector (ENU, m/s, the direction the air moves) for a meteorological report: speed
// and the direction the wind blows FROM, degrees clockwise from north.
Eigen::Vector3d wind_from_report(double speed_mps, double from_direction_deg);

struct TurbulenceParams {
  bool enabled = true;
  double reference_altitude_m = 50.0;  // h of the Dryden intensities and scale lengths
  double sample_period_s = 0.05;
};

class WindField {
 public:
  // mean_W_mps: the mean wind; seed and stream name select the turbulence sequence.
  WindField(const Eigen::Vector3d& mean_W_mps, const TurbulenceParams& turbulence, uint64_t seed);

  // The wind at time t_s (>= 0). Queries may go back up to 10 minutes behind the latest one.
  Eigen::Vector3d wind_W_mps(double t_s);

  const Eigen::Vector3d& mean_W_mps() const { return mean_W_mps_; }
  // Intensities (standard deviations) along, across and vertical, m/s.
  const Eigen::Vector3d& sigma_mps() const { return sigma_mps_; }
  const Eigen::Vector3d& correlation_time_s() const { return tau_s_; }

 private:
  Eigen::Vector3d sample_gust(std::size_t k);

  Eigen::Vector3d mean_W_mps_;
  TurbulenceParams params_;
  Eigen::Vector3d sigma_mps_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d tau_s_ = Eigen::Vector3d::Ones();
  Eigen::Vector3d along_W_, across_W_;
  common::Rng rng_;
  std::deque<Eigen::Vector3d> samples_;  // gusts (along, across, vertical) at first_index_ + i
  std::size_t first_index_ = 0;
};

}  // namespace a3::dynamics
