// Simulated sensors.
#include "bridge/sim/sensor_model.hpp"

#include <cmath>

#include "bridge/fc/state_estimator.hpp"

namespace a3::bridge {
namespace {

Eigen::Vector3d noise3(common::Rng& rng, double sigma) {
  return {sigma * rng.normal(), sigma * rng.normal(), sigma * rng.normal()};
}

}  // namespace

SensorModel::SensorModel(SensorNoise noise, uint64_t seed)
    : noise_(noise),
      imu_(common::RngStreams(seed).stream("sensors.imu")),
      gnss_(common::RngStreams(seed).stream("sensors.gnss")),
      baro_(common::RngStreams(seed).stream("sensors.baro")),
      mag_(common::RngStreams(seed).stream("sensors.mag")) {}

Eigen::Vector3d SensorModel::gyro_B_radps(const TruthSample& t) { return t.w_B_radps + noise3(imu_, noise_.gyro_radps); }

Eigen::Vector3d SensorModel::accel_B_mps2(const TruthSample& t) {
  return t.specific_force_B_mps2 + noise3(imu_, noise_.accel_mps2);
}

Eigen::Vector3d SensorModel::gnss_position_W_m(const TruthSample& t) {
  return t.p_W_m + Eigen::Vector3d(noise_.gnss_horizontal_m * gnss_.normal(), noise_.gnss_horizontal_m * gnss_.normal(),
                                   noise_.gnss_vertical_m * gnss_.normal());
}

Eigen::Vector3d SensorModel::gnss_velocity_W_mps(const TruthSample& t) {
  return t.v_W_mps + noise3(gnss_, noise_.gnss_velocity_mps);
}

double SensorModel::static_pressure_Pa(const TruthSample& t, double home_msl_m) {
  return isa_pressure_Pa(home_msl_m + t.p_W_m.z()) + noise_.baro_pressure_Pa * baro_.normal();
}

Eigen::Vector3d SensorModel::magnetic_field_B_gauss(const TruthSample& t) {
  const Eigen::Vector3d field_W = kEarthFieldGauss * earth_field_direction_W();
  return t.q_WB.conjugate() * field_W + noise3(mag_, noise_.mag_gauss);
}

}  // namespace a3::bridge
