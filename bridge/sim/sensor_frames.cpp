// Sensor messages from the true state.
#include "bridge/sim/sensor_frames.hpp"

#include <algorithm>
#include <cmath>

#include "bridge/nodes/frames.hpp"

namespace a3::bridge {
namespace {

bool finite(const double* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

std::array<float, 3> to_array(const Eigen::Vector3d& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

}  // namespace

bool vehicle_state_is_valid(const a3lcm::vehicle_state_t& s) {
  if (!finite(s.p_W_m, 3) || !finite(s.v_W_mps, 3) || !finite(s.q_WB, 4) || !finite(s.w_B_radps, 3) ||
      !finite(s.a_B_mps2, 3) || !std::isfinite(s.battery_pct) || !std::isfinite(s.battery_voltage_v) ||
      !std::isfinite(s.power_w)) {
    return false;
  }
  const double norm = std::sqrt(s.q_WB[0] * s.q_WB[0] + s.q_WB[1] * s.q_WB[1] + s.q_WB[2] * s.q_WB[2] +
                                s.q_WB[3] * s.q_WB[3]);
  return std::abs(norm - 1.0) < 1e-3;
}

TruthSample truth_from_state(const a3lcm::vehicle_state_t& s) {
  TruthSample t;
  t.t_s = static_cast<double>(s.utime_us) * 1e-6;
  t.p_W_m = {s.p_W_m[0], s.p_W_m[1], s.p_W_m[2]};
  t.v_W_mps = {s.v_W_mps[0], s.v_W_mps[1], s.v_W_mps[2]};
  t.q_WB = Eigen::Quaterniond(s.q_WB[0], s.q_WB[1], s.q_WB[2], s.q_WB[3]).normalized();
  t.w_B_radps = {s.w_B_radps[0], s.w_B_radps[1], s.w_B_radps[2]};
  t.specific_force_B_mps2 = {s.a_B_mps2[0], s.a_B_mps2[1], s.a_B_mps2[2]};
  return t;
}

void ImuIntegrator::add(double t_s, const Eigen::Vector3d& gyro, const Eigen::Vector3d& accel) {
  const double dt = t_s - last_t_s_;
  if (have_sample_ && dt > 0.0 && dt <= max_gap_s_) {
    gyro_integral_ += 0.5 * (gyro_ + gyro) * dt;
    accel_integral_ += 0.5 * (accel_ + accel) * dt;
    interval_s_ += dt;
  } else {
    // First sample, or a gap: the integral restarts (a report now carries no interval).
    gyro_integral_.setZero();
    accel_integral_.setZero();
    interval_s_ = 0.0;
  }
  have_sample_ = true;
  last_t_s_ = t_s;
  gyro_ = gyro;
  accel_ = accel;
}

AhrsRawImu ImuIntegrator::take_report(uint64_t timestamp_us) {
  AhrsRawImu m;
  m.timestamp.usec = timestamp_us;
  m.rate_gyro_latest = to_array(flu_frd(gyro_));
  m.accelerometer_latest = to_array(flu_frd(accel_));
  if (interval_s_ > 0.0) {
    m.integration_interval = static_cast<float>(interval_s_);
    m.rate_gyro_integral = to_array(flu_frd(gyro_integral_));
    m.accelerometer_integral = to_array(flu_frd(accel_integral_));
  }
  gyro_integral_.setZero();
  accel_integral_.setZero();
  interval_s_ = 0.0;
  return m;
}

GnssFix2 make_gnss_fix(uint64_t timestamp_us, const LocalFrame& frame, const Eigen::Vector3d& p_W_m,
                       const Eigen::Vector3d& v_W_mps) {
  const Geodetic g = frame.to_geodetic(p_W_m);
  GnssFix2 m;
  m.timestamp.usec = timestamp_us;
  m.gnss_time_standard = GnssFix2::kTimeStandardNone;
  m.longitude_deg_1e8 = std::llround(g.longitude_deg * 1e8);
  m.latitude_deg_1e8 = std::llround(g.latitude_deg * 1e8);
  m.height_ellipsoid_mm = static_cast<int32_t>(std::lround(g.height_m * 1e3));
  m.height_msl_mm = m.height_ellipsoid_mm;
  m.ned_velocity = to_array(enu_ned(v_W_mps));
  m.sats_used = 14;
  m.status = GnssFix2::kStatus3dFix;
  m.mode = GnssFix2::kModeSingle;
  m.pdop = 1.2f;
  return m;
}

StaticPressure make_static_pressure(double pressure_Pa, double sigma_Pa) {
  StaticPressure m;
  m.static_pressure = static_cast<float>(pressure_Pa);
  m.static_pressure_variance = static_cast<float>(sigma_Pa * sigma_Pa);
  return m;
}

StaticTemperature make_static_temperature(double temperature_K) {
  StaticTemperature m;
  m.static_temperature = static_cast<float>(temperature_K);
  m.static_temperature_variance = 0.25f;
  return m;
}

MagneticFieldStrength2 make_magnetic_field(const Eigen::Vector3d& field_B_gauss_flu, double sigma_gauss) {
  MagneticFieldStrength2 m;
  m.magnetic_field_ga = to_array(flu_frd(field_B_gauss_flu));
  const float variance = static_cast<float>(sigma_gauss * sigma_gauss);
  // Diagonal covariance: DroneCAN's 3-element form.
  for (int i = 0; i < 3; ++i) m.magnetic_field_covariance.push_back(variance);
  return m;
}

BatteryInfo make_battery_info(const a3lcm::vehicle_state_t& s, double average_power_W) {
  BatteryInfo m;
  m.temperature = 298.15f;
  m.voltage = static_cast<float>(s.battery_voltage_v);
  m.current = s.battery_voltage_v > 0.1 ? static_cast<float>(s.power_w / s.battery_voltage_v) : 0.0f;
  m.average_power_10sec = static_cast<float>(average_power_W);
  m.status_flags = BatteryInfo::kFlagInUse;
  m.state_of_health_pct = BatteryInfo::kStateOfHealthUnknown;
  m.state_of_charge_pct = static_cast<uint8_t>(std::lround(std::clamp(s.battery_pct, 0.0, 100.0)));
  m.state_of_charge_pct_stdev = 1;  // the integer percent's rounding
  m.battery_id = 0;
  m.model_name = text_array<31>("a3rig-sim");
  return m;
}

}  // namespace a3::bridge
