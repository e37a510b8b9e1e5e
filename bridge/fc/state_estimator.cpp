// Complementary attitude filter and per-axis position Kalman filters.
#include "bridge/fc/state_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace a3::bridge {
namespace {
constexpr double kGravity_mps2 = 9.80665;
constexpr double kInclination_rad = 63.0 * M_PI / 180.0;
}  // namespace

Eigen::Vector3d earth_field_direction_W() {
  return {0.0, std::cos(kInclination_rad), -std::sin(kInclination_rad)};
}

StateEstimator::StateEstimator(EstimatorNoise noise) : noise_(noise) {}

void StateEstimator::AxisFilter::predict(double a, double dt, double accel_sigma) {
  p += v * dt + 0.5 * a * dt * dt;
  v += a * dt;
  const double q = accel_sigma * accel_sigma;
  const double dt2 = dt * dt;
  // P = F P F' + Q, F = [1 dt; 0 1], Q = q [dt⁴/4 dt³/2; dt³/2 dt²]
  const double pp = P[0] + dt * (P[1] + P[2]) + dt2 * P[3] + q * dt2 * dt2 / 4.0;
  const double pv = P[1] + dt * P[3] + q * dt2 * dt / 2.0;
  const double vv = P[3] + q * dt2;
  P = {pp, pv, pv, vv};
}

void StateEstimator::AxisFilter::correct_position(double z, double sigma) {
  const double s = P[0] + sigma * sigma;
  const double kp = P[0] / s, kv = P[2] / s;
  const double r = z - p;
  p += kp * r;
  v += kv * r;
  P = {(1 - kp) * P[0], (1 - kp) * P[1], P[2] - kv * P[0], P[3] - kv * P[1]};
}

void StateEstimator::AxisFilter::correct_velocity(double z, double sigma) {
  const double s = P[3] + sigma * sigma;
  const double kp = P[1] / s, kv = P[3] / s;
  const double r = z - v;
  p += kp * r;
  v += kv * r;
  P = {P[0] - kp * P[2], P[1] - kp * P[3], (1 - kv) * P[2], (1 - kv) * P[3]};
}

void StateEstimator::initialise_attitude() {
  // Roll and pitch from the averaged gravity reading, yaw from the magnetometer.
  const Eigen::Vector3d up_B = (accel_sum_ / accel_count_).normalized();
  const double roll = std::atan2(up_B.y(), up_B.z());
  const double pitch = std::atan2(-up_B.x(), std::hypot(up_B.y(), up_B.z()));
  const Eigen::Quaterniond tilt = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  double yaw = 0.0;
  if (have_field_) {
    const Eigen::Vector3d f = tilt * last_field_B_;  // horizontal frame with yaw 0
    // The field points north; in a frame yawed by ψ, north is at angle π/2 - ψ.
    yaw = M_PI / 2 - std::atan2(f.y(), f.x());
  }
  state_.q_WB = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * tilt;
  state_.attitude_valid = true;
}

void StateEstimator::on_imu(double t_s, const Eigen::Vector3d& gyro, const Eigen::Vector3d& accel) {
  state_.w_B_radps = gyro;
  state_.accel_B_mps2 = accel;
  state_.time_s = t_s;
  if (!state_.attitude_valid) {
    accel_sum_ += accel;
    if (++accel_count_ >= 20 && have_field_) initialise_attitude();
    last_imu_t_s_ = t_s;
    return;
  }
  const double dt = last_imu_t_s_ < 0.0 ? 0.0 : std::clamp(t_s - last_imu_t_s_, 0.0, 0.05);
  last_imu_t_s_ = t_s;
  if (dt <= 0.0) return;
  // Attitude: integrate the body rate.
  const double angle = gyro.norm() * dt;
  if (angle > 0.0) state_.q_WB = state_.q_WB * Eigen::Quaterniond(Eigen::AngleAxisd(angle, gyro.normalized()));
  // Slow correction of roll and pitch toward gravity, only when the specific force is ~g.
  if (std::abs(accel.norm() - kGravity_mps2) < 0.3 && gyro.norm() < 0.5) {
    const Eigen::Vector3d measured_up_W = state_.q_WB * accel.normalized();
    const Eigen::Vector3d correction = measured_up_W.cross(Eigen::Vector3d::UnitZ());
    const double gain = dt / noise_.attitude_correction_time_s;
    state_.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(gain * correction.norm(),
                                                       correction.norm() > 1e-12 ? correction.normalized() : Eigen::Vector3d::UnitZ())) *
                  state_.q_WB;
  }
  state_.q_WB.normalize();
  // Position and velocity: world acceleration from the specific force.
  const Eigen::Vector3d a_W = state_.q_WB * accel - Eigen::Vector3d(0, 0, kGravity_mps2);
  if (have_gnss_) {
    for (int i = 0; i < 3; ++i) axes_[i].predict(a_W[i], dt, noise_.accel_mps2);
    for (int i = 0; i < 3; ++i) {
      state_.p_W_m[i] = axes_[i].p;
      state_.v_W_mps[i] = axes_[i].v;
    }
  }
}

void StateEstimator::on_gnss(double, const Eigen::Vector3d& p, const Eigen::Vector3d& v) {
  if (!have_gnss_) {
    for (int i = 0; i < 3; ++i) {
      axes_[i].p = p[i];
      axes_[i].v = v[i];
      axes_[i].P = {noise_.gnss_position_m * noise_.gnss_position_m, 0.0, 0.0,
                    noise_.gnss_velocity_mps * noise_.gnss_velocity_mps};
    }
    have_gnss_ = true;
    state_.position_valid = true;
  }
  for (int i = 0; i < 3; ++i) {
    const double sigma = i == 2 ? 1.5 * noise_.gnss_position_m : noise_.gnss_position_m;
    axes_[i].correct_position(p[i], sigma);
    axes_[i].correct_velocity(v[i], noise_.gnss_velocity_mps);
    state_.p_W_m[i] = axes_[i].p;
    state_.v_W_mps[i] = axes_[i].v;
  }
}

void StateEstimator::on_baro(double, double altitude_m) {
  if (!have_gnss_) return;
  axes_[2].correct_position(altitude_m, noise_.baro_altitude_m);
  state_.p_W_m.z() = axes_[2].p;
  state_.v_W_mps.z() = axes_[2].v;
}

void StateEstimator::on_magnetometer(double t_s, const Eigen::Vector3d& field_B) {
  if (field_B.norm() < 1e-9) return;
  last_field_B_ = field_B.normalized();
  have_field_ = true;
  if (!state_.attitude_valid) return;
  // Heading error: the measured field's horizontal direction against north.
  const Eigen::Vector3d f_W = state_.q_WB * last_field_B_;
  const Eigen::Vector3d expected = earth_field_direction_W();
  const double measured_heading = std::atan2(f_W.y(), f_W.x());
  const double expected_heading = std::atan2(expected.y(), expected.x());
  double error = expected_heading - measured_heading;
  error = std::atan2(std::sin(error), std::cos(error));
  static_cast<void>(t_s);
  const double gain = 1.0 / (noise_.heading_correction_time_s * 50.0);  // per sample at ~50 Hz
  state_.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(gain * error, Eigen::Vector3d::UnitZ())) * state_.q_WB;
  state_.q_WB.normalize();
}

}  // namespace a3::bridge
