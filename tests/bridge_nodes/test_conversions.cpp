// The conversions between the rig's messages, DroneCAN messages and the fc's types: frames
// (FLU/FRD, ENU/NED), ESC scaling, commands and status, sensor messages made by the bridge
// and read back by the fc, and the sensors' report schedule.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "bridge/dronecan/serialization.hpp"
#include "bridge/nodes/esc_scaling.hpp"
#include "bridge/nodes/fc_messages.hpp"
#include "bridge/nodes/frames.hpp"
#include "bridge/nodes/sensor_readings.hpp"
#include "bridge/sim/rate_schedule.hpp"
#include "bridge/sim/sensor_frames.hpp"

namespace a3::bridge {
namespace {

// Encodes and decodes a message as it crosses the bus (float16 fields lose precision here).
template <class Msg>
Msg over_the_wire(const Msg& in) {
  Payload payload;
  EXPECT_TRUE(encode_payload(in, payload).ok());
  Msg out{};
  EXPECT_TRUE(decode_payload(payload.data(), payload.size, out).ok());
  return out;
}

TEST(Frames, BodyAndWorldSwapsAreTheirOwnInverse) {
  const Eigen::Vector3d v(1, 2, 3);
  EXPECT_EQ(flu_frd(v), Eigen::Vector3d(1, -2, -3));
  EXPECT_EQ(enu_ned(v), Eigen::Vector3d(2, 1, -3));
  EXPECT_EQ(flu_frd(flu_frd(v)), v);
  EXPECT_EQ(enu_ned(enu_ned(v)), v);
}

TEST(EscScaling, ThrottleToRawAndBack) {
  EXPECT_EQ(throttle_to_esc_raw(0.0), 0);
  EXPECT_EQ(throttle_to_esc_raw(1.0), 8191);
  EXPECT_EQ(throttle_to_esc_raw(1.7), 8191);
  EXPECT_EQ(throttle_to_esc_raw(-0.2), 0);
  EXPECT_EQ(throttle_to_esc_raw(std::nan("")), 0);
  EXPECT_EQ(throttle_to_esc_raw(0.5), 4096);
  EXPECT_DOUBLE_EQ(esc_raw_to_throttle(8191), 1.0);
  EXPECT_DOUBLE_EQ(esc_raw_to_throttle(-300), 0.0);
  for (double t = 0.0; t <= 1.0; t += 0.0137) EXPECT_NEAR(esc_raw_to_throttle(throttle_to_esc_raw(t)), t, 0.5 / 8191);
}

TEST(FcMessages, CommandKeepsCodesAndTurnsHugeValuesIntoInfinity) {
  a3lcm::fc_command_t c{};
  c.seq = 77;
  c.command = a3lcm::fc_command_t::GOTO;
  c.target_W_m[0] = 12.5;
  c.target_W_m[1] = 1e300;
  c.target_W_m[2] = std::nan("");
  c.speed_limit_mps = 4.0;
  c.yaw_deg = std::nan("");
  EXPECT_TRUE(fc_command_has_nonfinite(c));
  const FcCommand can = over_the_wire(fc_command_to_can(c));
  EXPECT_EQ(can.seq, 77);
  EXPECT_EQ(can.command, FcCommand::kGoto);
  EXPECT_FLOAT_EQ(can.target_W_m[0], 12.5f);
  EXPECT_TRUE(std::isinf(can.target_W_m[1]));
  EXPECT_TRUE(std::isnan(can.target_W_m[2]));
  const FlightCommand f = flight_command_from_can(can);
  EXPECT_EQ(f.kind, FlightCommandKind::kGoto);
  EXPECT_TRUE(std::isnan(f.yaw_deg));  // NaN yaw: keep the heading
  c.target_W_m[1] = 3;
  c.target_W_m[2] = 10;
  EXPECT_FALSE(fc_command_has_nonfinite(c));  // a NaN yaw is allowed

  c.command = -3;  // not a command: passes to the fc, which refuses it as unknown
  EXPECT_EQ(fc_command_to_can(c).command, 253);
  EXPECT_EQ(static_cast<int>(flight_command_from_can(fc_command_to_can(c)).kind), -3);
}

TEST(FcMessages, StatusCarriesTheRefusalReasonAsText) {
  FlightStatus s;
  s.mode = FcMode::kGoto;
  s.armed = true;
  s.failsafe = FcFailsafe::kLowBattery;
  s.p_W_m = {1.5, -2.25, 10.0};
  s.battery_pct = 42.0;
  s.yaw_deg = 90.0;
  s.last_command_seq = 9;
  s.last_command_accepted = false;
  s.last_refusal = FcRefusal::kOutsideGeofence;
  const a3lcm::fc_status_t out = fc_status_from_can(over_the_wire(fc_status_to_can(s)), 1234);
  EXPECT_EQ(out.utime_us, 1234);
  EXPECT_EQ(out.mode, int8_t{a3lcm::fc_status_t::GOTO});
  EXPECT_TRUE(out.armed);
  EXPECT_EQ(out.failsafe, int8_t{a3lcm::fc_status_t::FAILSAFE_LOW_BATTERY});
  EXPECT_DOUBLE_EQ(out.p_W_m[1], -2.25);
  EXPECT_DOUBLE_EQ(out.battery_pct, 42.0);
  EXPECT_DOUBLE_EQ(out.yaw_deg, 90.0);
  EXPECT_EQ(out.last_command_seq, 9);
  EXPECT_FALSE(out.last_command_accepted);
  EXPECT_EQ(out.last_command_reason, "outside the geofence");
  // The fc's refusal texts and the CAN reason texts are the same words.
  for (uint8_t r = 0; r <= FcStatus::kLastReason; ++r) {
    EXPECT_EQ(std::string(to_string(static_cast<FcRefusal>(r))), std::string(fc_reason_text(r))) << int(r);
  }
}

TEST(RateSchedule, TakesTheFreshestSampleAtEachTickAndNeverRepeatsOne) {
  const auto count = [](double rate_hz, int64_t sample_period_us, int64_t duration_us) {
    RateSchedule s(rate_hz);
    int n = 0;
    for (int64_t t = 0; t < duration_us; t += sample_period_us) n += s.due(t);
    return n;
  };
  EXPECT_EQ(count(200, 4000, 1'000'000), 200);  // states at 250 Hz: 4 of 5
  EXPECT_EQ(count(200, 5000, 1'000'000), 200);  // at 200 Hz: every one
  EXPECT_EQ(count(200, 10000, 1'000'000), 100);  // at 100 Hz: every one, no repeats
  EXPECT_EQ(count(10, 4000, 1'000'000), 10);
  EXPECT_EQ(count(50, 4000, 1'000'000), 50);
  EXPECT_EQ(count(5, 4000, 10'000'000), 50);

  RateSchedule s(10);
  EXPECT_TRUE(s.due(1'000'000));
  EXPECT_FALSE(s.due(1'050'000));
  EXPECT_FALSE(s.due(1'099'700));
  EXPECT_TRUE(s.due(1'099'800));  // 200 us short of the tick: on it
  EXPECT_FALSE(s.due(1'100'000));
  EXPECT_TRUE(s.due(5'000'000));  // after a gap: at once, then on a new grid
  EXPECT_FALSE(s.due(5'050'000));
  EXPECT_TRUE(s.due(100'000));    // time went back: start over
  EXPECT_THROW(RateSchedule(0.0), std::invalid_argument);
}

TEST(SensorFrames, ImuReportsTheMeanOverItsIntervalInFrdAndTheFcReadsFlu) {
  ImuIntegrator imu;
  // A rate ramping linearly: the trapezoidal mean is exact.
  for (int k = 0; k <= 2; ++k) {
    const double t = 0.004 * k;
    imu.add(t, Eigen::Vector3d(0.1 + t, 0.2, -0.3), Eigen::Vector3d(0.5, -0.25, 9.80665 + 10 * t));
  }
  const AhrsRawImu m = over_the_wire(imu.take_report(8000));
  EXPECT_NEAR(m.integration_interval, 0.008, 1e-9);
  EXPECT_NEAR(m.rate_gyro_latest[1], -0.2, 1e-3);  // FRD on the wire
  EXPECT_NEAR(m.accelerometer_latest[2], -(9.80665 + 0.08), 1e-2);
  const auto r = imu_reading(m);
  ASSERT_TRUE(r.has_value());
  EXPECT_TRUE(r->from_integral);
  EXPECT_NEAR(r->gyro_B_radps.x(), 0.1 + 0.004, 1e-6);  // the mean, float32
  EXPECT_NEAR(r->gyro_B_radps.y(), 0.2, 1e-6);
  EXPECT_NEAR(r->accel_B_mps2.z(), 9.80665 + 0.04, 1e-5);
  // The next report starts a new interval.
  imu.add(0.012, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.8));
  EXPECT_NEAR(imu.take_report(12000).integration_interval, 0.004, 1e-9);
  // After a gap the report has no interval: the fc uses the latest samples.
  imu.add(0.5, Eigen::Vector3d(0.01, 0, 0), Eigen::Vector3d(0, 0, 9.8));
  const AhrsRawImu gap = over_the_wire(imu.take_report(500000));
  EXPECT_EQ(gap.integration_interval, 0.0f);
  ASSERT_TRUE(imu_reading(gap).has_value());
  EXPECT_FALSE(imu_reading(gap)->from_integral);
  EXPECT_NEAR(imu_reading(gap)->accel_B_mps2.z(), 9.8, 1e-2);
}

TEST(SensorFrames, GnssBaroMagAndBatteryReadBackInTheRigsFrames) {
  const LocalFrame frame(kDefaultHome);
  const Eigen::Vector3d p(123.456, -78.9, 42.0), v(3.0, -1.0, 0.5);
  const auto g = gnss_reading(over_the_wire(make_gnss_fix(5, frame, p, v)), frame);
  ASSERT_TRUE(g.has_value());
  EXPECT_NEAR((g->p_W_m - p).norm(), 0.0, 0.003);  // 1e-8 degree and millimetre resolution
  EXPECT_NEAR((g->v_W_mps - v).norm(), 0.0, 1e-6);

  const double altitude = 37.5;
  const auto baro = baro_altitude_m(over_the_wire(make_static_pressure(isa_pressure_Pa(488.0 + altitude), 0.9)), 488.0);
  ASSERT_TRUE(baro.has_value());
  EXPECT_NEAR(*baro, altitude, 0.01);

  const Eigen::Vector3d field(0.1, 0.2, -0.4);
  const auto mag = magnetic_field_B(over_the_wire(make_magnetic_field(field, 0.002)));
  ASSERT_TRUE(mag.has_value());
  EXPECT_NEAR((*mag - field).norm(), 0.0, 1e-3);  // float16

  a3lcm::vehicle_state_t s{};
  s.battery_pct = 24.6;
  s.battery_voltage_v = 11.1;
  s.power_w = 222.0;
  const BatteryInfo b = over_the_wire(make_battery_info(s, 210.0));
  EXPECT_EQ(b.state_of_charge_pct, 25);
  EXPECT_NEAR(b.current, 20.0, 0.05);
  EXPECT_NEAR(*battery_percent(b), 25.0, 1e-9);
}

TEST(SensorReadings, UnusableMessagesGiveNothing) {
  AhrsRawImu imu;
  imu.rate_gyro_latest = {std::numeric_limits<float>::quiet_NaN(), 0, 0};
  EXPECT_FALSE(imu_reading(imu).has_value());
  imu.rate_gyro_latest = {0, 0, 0};
  imu.integration_interval = 0.005f;
  imu.accelerometer_integral = {0, 0, std::numeric_limits<float>::infinity()};
  EXPECT_FALSE(imu_reading(imu).has_value());

  const LocalFrame frame;
  GnssFix2 fix = make_gnss_fix(0, frame, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  fix.status = GnssFix2::kStatus2dFix;
  EXPECT_FALSE(gnss_reading(fix, frame).has_value());
  fix.status = GnssFix2::kStatus3dFix;
  fix.latitude_deg_1e8 = 95'00000000LL;
  EXPECT_FALSE(gnss_reading(fix, frame).has_value());

  StaticPressure p;
  p.static_pressure = -5.0f;
  EXPECT_FALSE(baro_altitude_m(p, 0.0).has_value());
  p.static_pressure = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(baro_altitude_m(p, 0.0).has_value());

  EXPECT_FALSE(magnetic_field_B(MagneticFieldStrength2{}).has_value());  // all zero: no reading
  BatteryInfo b;
  b.state_of_charge_pct = BatteryInfo::kStateOfChargeUnknown;
  EXPECT_FALSE(battery_percent(b).has_value());
}

TEST(SensorFrames, StatesWithNaNOrABadAttitudeAreInvalid) {
  a3lcm::vehicle_state_t s{};
  s.q_WB[0] = 1.0;
  EXPECT_TRUE(vehicle_state_is_valid(s));
  s.v_W_mps[1] = std::nan("");
  EXPECT_FALSE(vehicle_state_is_valid(s));
  s.v_W_mps[1] = 0;
  s.q_WB[0] = 0.5;
  EXPECT_FALSE(vehicle_state_is_valid(s));
}

}  // namespace
}  // namespace a3::bridge
