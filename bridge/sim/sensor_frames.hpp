// The bridge's sensors: DroneCAN sensor messages made from the true vehicle state (A3_STATE)
// with the SensorModel's seeded noise. The IMU samples the truth at every state message and
// each RawIMU carries the latest sample (float16) and the trapezoidal integral of the samples
// since the previous RawIMU (float32, with its integration interval), as a real IMU that
// samples faster than it reports does. GNSS reports WGS-84 around the home point (geoid
// separation taken as 0: height above MSL = height above the ellipsoid); the barometer reports
// ISA static pressure at home height + z.
#pragma once

#include <Eigen/Core>

#include <cstdint>

#include "a3lcm/vehicle_state_t.hpp"
#include "bridge/dronecan/msg/ahrs.hpp"
#include "bridge/dronecan/msg/air_data.hpp"
#include "bridge/dronecan/msg/gnss.hpp"
#include "bridge/dronecan/msg/power.hpp"
#include "bridge/fc/geo.hpp"
#include "bridge/sim/sensor_model.hpp"

namespace a3::bridge {

// False when any field the sensors read is NaN or infinite, or the attitude is not a rotation.
bool vehicle_state_is_valid(const a3lcm::vehicle_state_t& state);
TruthSample truth_from_state(const a3lcm::vehicle_state_t& state);

// Accumulates IMU samples (FLU) between reports.
class ImuIntegrator {
 public:
  // Samples more than max_gap_s apart (or out of order) restart the integral.
  explicit ImuIntegrator(double max_gap_s = 0.1) : max_gap_s_(max_gap_s) {}
  void add(double t_s, const Eigen::Vector3d& gyro_B_radps, const Eigen::Vector3d& accel_B_mps2);
  // The RawIMU for the samples so far (frames converted to FRD); starts the next interval.
  AhrsRawImu take_report(uint64_t timestamp_us);
  void reset() { *this = ImuIntegrator(max_gap_s_); }

 private:
  double max_gap_s_;
  bool have_sample_ = false;
  double last_t_s_ = 0.0;
  Eigen::Vector3d gyro_ = Eigen::Vector3d::Zero(), accel_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_integral_ = Eigen::Vector3d::Zero(), accel_integral_ = Eigen::Vector3d::Zero();
  double interval_s_ = 0.0;
};

GnssFix2 make_gnss_fix(uint64_t timestamp_us, const LocalFrame& frame, const Eigen::Vector3d& p_W_m,
                       const Eigen::Vector3d& v_W_mps);
StaticPressure make_static_pressure(double pressure_Pa, double sigma_Pa);
StaticTemperature make_static_temperature(double temperature_K);
MagneticFieldStrength2 make_magnetic_field(const Eigen::Vector3d& field_B_gauss_flu, double sigma_gauss);
// average_power_W: the power averaged over the last ~10 s.
BatteryInfo make_battery_info(const a3lcm::vehicle_state_t& state, double average_power_W);

}  // namespace a3::bridge
