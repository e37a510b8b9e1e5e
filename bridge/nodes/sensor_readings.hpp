// The fc's side of the sensor messages: what each DroneCAN message says in the rig's frames
// (body FLU, world ENU around the home point), or nothing when the message is not usable
// (NaN or infinite values, no 3-D fix, pressure or percent out of range). The fc counts and
// logs what is dropped; nothing here throws.
#pragma once

#include <Eigen/Core>

#include <optional>

#include "bridge/dronecan/msg/ahrs.hpp"
#include "bridge/dronecan/msg/air_data.hpp"
#include "bridge/dronecan/msg/gnss.hpp"
#include "bridge/dronecan/msg/power.hpp"
#include "bridge/fc/geo.hpp"

namespace a3::bridge {

struct ImuReading {
  Eigen::Vector3d gyro_B_radps;   // FLU
  Eigen::Vector3d accel_B_mps2;   // FLU, specific force
  bool from_integral = false;     // the interval means (float32), not the latest (float16)
};
// The means over the integration interval when the message has one (0 < interval ≤ 0.1 s),
// else the latest samples.
std::optional<ImuReading> imu_reading(const AhrsRawImu& m);

struct GnssReading {
  Eigen::Vector3d p_W_m;
  Eigen::Vector3d v_W_mps;
};
std::optional<GnssReading> gnss_reading(const GnssFix2& m, const LocalFrame& frame);

// Altitude above home (ISA) from static pressure; home_msl_m is the home point's height.
std::optional<double> baro_altitude_m(const StaticPressure& m, double home_msl_m);
std::optional<Eigen::Vector3d> magnetic_field_B(const MagneticFieldStrength2& m);  // FLU, gauss
std::optional<double> battery_percent(const BatteryInfo& m);

}  // namespace a3::bridge
