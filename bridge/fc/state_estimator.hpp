// The flight controller's state estimate from its sensors, as they arrive over CAN:
// attitude by integrating the gyro, corrected slowly toward the accelerometer's gravity (when
// the vehicle is not accelerating) and the magnetometer's heading (a complementary filter);
// position and velocity per axis by a two-state Kalman filter driven by the accelerometer
// (rotated into the world) and corrected by GNSS position and velocity and barometric altitude.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

namespace a3::bridge {

struct EstimatorNoise {
  double accel_mps2 = 0.25;       // process noise of the position filter: accelerometer noise plus
                                  // what the attitude estimate gets wrong (a tilt error is a bias)
  double gnss_position_m = 0.3;   // horizontal; vertical is 1.5 × this
  double gnss_velocity_mps = 0.05;
  double baro_altitude_m = 0.1;
  double attitude_correction_time_s = 10.0;  // accelerometer → roll/pitch
  double heading_correction_time_s = 5.0;    // magnetometer → yaw
};

struct EstimatedState {
  double time_s = 0.0;
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_W_mps = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();
  Eigen::Vector3d w_B_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_B_mps2 = Eigen::Vector3d::Zero();  // last specific force
  bool attitude_valid = false;
  bool position_valid = false;
  bool valid() const { return attitude_valid && position_valid; }
};

// The Earth's magnetic field direction in the world frame (ENU), unit vector: north and down,
// inclination 63° (central Europe), declination 0.
Eigen::Vector3d earth_field_direction_W();

class StateEstimator {
 public:
  explicit StateEstimator(EstimatorNoise noise = {});

  void on_imu(double t_s, const Eigen::Vector3d& gyro_B_radps, const Eigen::Vector3d& accel_B_mps2);
  void on_gnss(double t_s, const Eigen::Vector3d& p_W_m, const Eigen::Vector3d& v_W_mps);
  void on_baro(double t_s, double altitude_m);
  void on_magnetometer(double t_s, const Eigen::Vector3d& field_B);

  const EstimatedState& state() const { return state_; }

 private:
  struct AxisFilter {
    double p = 0.0, v = 0.0;
    std::array<double, 4> P{100.0, 0.0, 0.0, 100.0};  // covariance [pp pv; vp vv]
    void predict(double a, double dt, double accel_sigma);
    void correct_position(double z, double sigma);
    void correct_velocity(double z, double sigma);
  };
  void initialise_attitude();

  EstimatorNoise noise_;
  EstimatedState state_;
  std::array<AxisFilter, 3> axes_;
  double last_imu_t_s_ = -1.0;
  Eigen::Vector3d accel_sum_ = Eigen::Vector3d::Zero();
  int accel_count_ = 0;
  Eigen::Vector3d last_field_B_ = Eigen::Vector3d::Zero();
  bool have_field_ = false;
  bool have_gnss_ = false;
};

}  // namespace a3::bridge
