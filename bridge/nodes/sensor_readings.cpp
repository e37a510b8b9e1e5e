// Sensor messages to the fc's measurements.
#include "bridge/nodes/sensor_readings.hpp"

#include <cmath>

#include "bridge/fc/earth_model.hpp"
#include "bridge/nodes/frames.hpp"

namespace a3::bridge {
namespace {

Eigen::Vector3d vec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

constexpr double kMinPressure_Pa = 1000.0;    // ~ 31 km
constexpr double kMaxPressure_Pa = 120000.0;  // below sea level, deep

}  // namespace

std::optional<ImuReading> imu_reading(const AhrsRawImu& m) {
  ImuReading r;
  const double interval = m.integration_interval;
  if (std::isfinite(interval) && interval > 0.0 && interval <= 0.1) {
    r.gyro_B_radps = flu_frd(vec(m.rate_gyro_integral) / interval);
    r.accel_B_mps2 = flu_frd(vec(m.accelerometer_integral) / interval);
    r.from_integral = true;
  } else {
    r.gyro_B_radps = flu_frd(vec(m.rate_gyro_latest));
    r.accel_B_mps2 = flu_frd(vec(m.accelerometer_latest));
  }
  if (!r.gyro_B_radps.allFinite() || !r.accel_B_mps2.allFinite()) return std::nullopt;
  return r;
}

std::optional<GnssReading> gnss_reading(const GnssFix2& m, const LocalFrame& frame) {
  if (m.status != GnssFix2::kStatus3dFix) return std::nullopt;
  Geodetic g;
  g.latitude_deg = static_cast<double>(m.latitude_deg_1e8) * 1e-8;
  g.longitude_deg = static_cast<double>(m.longitude_deg_1e8) * 1e-8;
  g.height_m = static_cast<double>(m.height_ellipsoid_mm) * 1e-3;
  if (std::abs(g.latitude_deg) > 90.0 || std::abs(g.longitude_deg) > 180.0) return std::nullopt;
  GnssReading r;
  r.p_W_m = frame.to_enu(g);
  r.v_W_mps = enu_ned(vec(m.ned_velocity));
  if (!r.p_W_m.allFinite() || !r.v_W_mps.allFinite()) return std::nullopt;
  return r;
}

std::optional<double> baro_altitude_m(const StaticPressure& m, double home_msl_m) {
  const double p = m.static_pressure;
  if (!std::isfinite(p) || p < kMinPressure_Pa || p > kMaxPressure_Pa) return std::nullopt;
  return isa_altitude_m(p) - home_msl_m;
}

std::optional<Eigen::Vector3d> magnetic_field_B(const MagneticFieldStrength2& m) {
  const Eigen::Vector3d field = flu_frd(vec(m.magnetic_field_ga));
  if (!field.allFinite() || field.norm() < 1e-6) return std::nullopt;
  return field;
}

std::optional<double> battery_percent(const BatteryInfo& m) {
  if (m.state_of_charge_pct > 100) return std::nullopt;  // 127: unknown
  return static_cast<double>(m.state_of_charge_pct);
}

}  // namespace a3::bridge
