// The flight controller's sensors, simulated from the true vehicle state with seeded noise:
// IMU (gyro, accelerometer), GNSS (position and velocity), barometer (static pressure and
// temperature of the ISA atmosphere at the altitude), magnetometer (the Earth's field in the
// body frame) and battery. White Gaussian noise per sample, no biases; each sensor draws from its
// own named RNG stream.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>

#include "bridge/fc/earth_model.hpp"
#include "common/rng.hpp"

namespace a3::bridge {

struct SensorNoise {
  double gyro_radps = 0.003;
  double accel_mps2 = 0.03;
  double gnss_horizontal_m = 0.3;
  double gnss_vertical_m = 0.45;
  double gnss_velocity_mps = 0.05;
  double baro_pressure_Pa = 0.9;   // ≈ 0.08 m of altitude near sea level
  double mag_gauss = 0.002;
};

struct TruthSample {
  double t_s = 0.0;
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_W_mps = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();
  Eigen::Vector3d w_B_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d specific_force_B_mps2 = Eigen::Vector3d(0, 0, 9.80665);
};

class SensorModel {
 public:
  SensorModel(SensorNoise noise, uint64_t seed);

  Eigen::Vector3d gyro_B_radps(const TruthSample& t);
  Eigen::Vector3d accel_B_mps2(const TruthSample& t);
  Eigen::Vector3d gnss_position_W_m(const TruthSample& t);
  Eigen::Vector3d gnss_velocity_W_mps(const TruthSample& t);
  // home_msl_m: the height above sea level of ENU z = 0.
  double static_pressure_Pa(const TruthSample& t, double home_msl_m);
  Eigen::Vector3d magnetic_field_B_gauss(const TruthSample& t);

  const SensorNoise& noise() const { return noise_; }

 private:
  SensorNoise noise_;
  common::Rng imu_, gnss_, baro_, mag_;
};

}  // namespace a3::bridge
