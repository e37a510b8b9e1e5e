// Round trips of every message type through payload and frames, the project messages'
// exact bit layout, casts (saturation, truncation), tail array optimisation, and the errors
// a bad payload or bad JSON gives.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>
#include <vector>

#include "bridge/dronecan/data_type_table.hpp"
#include "bridge/dronecan/json_codec.hpp"
#include "bridge/dronecan/messages.hpp"
#include "bridge/dronecan/reassembler.hpp"
#include "bridge/dronecan/serialization.hpp"
#include "bridge/dronecan/transfer.hpp"

namespace a3::bridge {
namespace {

// Values chosen to be exact in float16 where a field is float16.
NodeStatus sample(NodeStatus*) { return {3600, NodeStatus::kHealthWarning, 1, 0, 0xBEEF}; }
EscRawCommand sample(EscRawCommand*) {
  EscRawCommand m;
  m.cmd = {0, 1, -1, 8191, -8192, 4096, 100, 200};
  return m;
}
EscStatus sample(EscStatus*) { return {7, 16.5f, -3.25f, 300.0f, -123456, 99, 31}; }
AhrsRawImu sample(AhrsRawImu*) {
  AhrsRawImu m;
  m.timestamp.usec = 72057594037927935ULL;  // 2^56 - 1
  m.integration_interval = 0.005f;
  m.rate_gyro_latest = {0.5f, -0.25f, 2.0f};
  m.rate_gyro_integral = {0.0025f, -0.00125f, 0.01f};
  m.accelerometer_latest = {0.125f, -0.5f, -9.8125f};
  m.accelerometer_integral = {1e-3f, -2e-3f, -0.049f};
  m.covariance = {0.5f, 0.25f, 0.125f};
  return m;
}
MagneticFieldStrength2 sample(MagneticFieldStrength2*) {
  MagneticFieldStrength2 m;
  m.sensor_id = 2;
  m.magnetic_field_ga = {0.25f, -0.125f, 0.5f};
  m.magnetic_field_covariance = {0.0625f};
  return m;
}
GnssFix2 sample(GnssFix2*) {
  GnssFix2 m;
  m.timestamp.usec = 123;
  m.gnss_timestamp.usec = 1700000000000000ULL;
  m.gnss_time_standard = GnssFix2::kTimeStandardGps;
  m.num_leap_seconds = 18;
  m.longitude_deg_1e8 = -68719476736;  // int37 minimum
  m.latitude_deg_1e8 = 68719476735;    // int37 maximum
  m.height_ellipsoid_mm = -67108864;   // int27 minimum
  m.height_msl_mm = 67108863;
  m.ned_velocity = {1.5f, -2.25f, 0.1f};
  m.sats_used = 63;
  m.status = GnssFix2::kStatus3dFix;
  m.mode = GnssFix2::kModeRtk;
  m.sub_mode = 1;
  m.covariance = {1.0f, 2.0f, 3.0f, 4.0f};
  m.pdop = 1.5f;
  GnssEcefPositionVelocity ecef;
  ecef.velocity_xyz = {0.5f, 1.5f, -2.5f};
  ecef.position_xyz_mm = {4000000000LL, -34359738368LL, 34359738367LL};
  ecef.covariance = {0.25f, 0.5f};
  m.ecef_position_velocity.push_back(ecef);
  return m;
}
StaticPressure sample(StaticPressure*) { return {101325.0f, 2.5f}; }
StaticTemperature sample(StaticTemperature*) { return {288.25f, 0.25f}; }
BatteryInfo sample(BatteryInfo*) {
  BatteryInfo m;
  m.temperature = 300.0f;
  m.voltage = 16.5f;
  m.current = 12.25f;
  m.average_power_10sec = 200.0f;
  m.remaining_capacity_wh = 40.0f;
  m.full_charge_capacity_wh = 60.0f;
  m.hours_to_full_charge = 0.0f;
  m.status_flags = BatteryInfo::kFlagInUse | BatteryInfo::kFlagBmsError;
  m.state_of_health_pct = 100;
  m.state_of_charge_pct = 67;
  m.state_of_charge_pct_stdev = 3;
  m.battery_id = 1;
  m.model_instance_id = 0xDEADBEEF;
  m.model_name = text_array<31>("a3rig simulated 4S LiPo 5 Ah");
  return m;
}
ActuatorArrayCommand sample(ActuatorArrayCommand*) {
  ActuatorArrayCommand m;
  for (uint8_t i = 0; i < 15; ++i) {
    m.commands.push_back({i, ActuatorCommand::kTypeUnitless, i / 16.0f});
  }
  return m;
}
ArmingStatus sample(ArmingStatus*) { return {ArmingStatus::kFullyArmed}; }
FcCommand sample(FcCommand*) {
  return {-7, FcCommand::kGoto, {50.5f, -20.25f, 10.0f}, 4.5f,
          std::numeric_limits<float>::quiet_NaN()};
}
FcStatus sample(FcStatus*) {
  FcStatus m;
  m.mode = FcStatus::kModeGoto;
  m.armed = true;
  m.failsafe = FcStatus::kFailsafeLowBattery;
  m.p_W_m = {1.5f, -2.5f, 10.125f};
  m.v_W_mps = {0.25f, 3.5f, -0.5f};
  m.yaw_deg = -90.0f;
  m.battery_pct = 42.5f;
  m.last_command_seq = 123456;
  m.last_command_accepted = false;
  m.last_command_reason = FcStatus::kReasonOutsideGeofence;
  return m;
}

SimClock sample(SimClock*) { return {(uint64_t{1} << 55) + 12345}; }  // 56 bits: beyond 2^32 us
FcCommandRefused sample(FcCommandRefused*) { return {99, 20600, FcCommand::kEmergencyStop, -7, 65535, 4000000000u}; }

// NaN != NaN: compare the JSON forms (NaN is null there) instead of operator==.
template <class Msg>
void expect_same(const Msg& a, const Msg& b) {
  EXPECT_EQ(message_to_json(a), message_to_json(b));
}

template <class Msg>
void round_trip_through_frames() {
  SCOPED_TRACE(std::string(Msg::kType.full_name));
  const Msg original = sample(static_cast<Msg*>(nullptr));
  Payload payload;
  std::vector<CanFrame> frames;
  const auto header = message_header<Msg>(42, 9, kPriorityHigh);
  ASSERT_TRUE(append_message_frames(original, header, payload, frames).ok());
  EXPECT_EQ(frames.size(), transfer_frame_count(payload.size));
  EXPECT_LE(payload.size * 8, Msg::kType.max_bit_length + 7);

  DataTypeTable table;
  table.add_message<Msg>();
  TransferReassembler reassembler(table);
  ReceivedTransfer transfer;
  FrameVerdict verdict = FrameVerdict::kIgnored;
  for (const auto& frame : frames) verdict = reassembler.accept(frame, 0, transfer);
  ASSERT_EQ(verdict, FrameVerdict::kTransferComplete);
  EXPECT_EQ(transfer.header, header);
  Msg decoded{};
  const CodecStatus status = decode_payload(transfer.payload, transfer.size, decoded);
  ASSERT_TRUE(status.ok()) << status.message(Msg::kType.full_name);
  expect_same(original, decoded);

  // And through JSON.
  expect_same(original, message_from_json<Msg>(message_to_json(original)));
}

TEST(MessageRoundTrip, EveryTypeSurvivesFramesAndJson) {
  std::apply([](auto... msgs) { (round_trip_through_frames<decltype(msgs)>(), ...); },
             MessageTypes{});
}

template <class T>
std::vector<uint8_t> le_bytes(T value) {
  std::vector<uint8_t> out(sizeof(T));
  std::memcpy(out.data(), &value, sizeof(T));
  return out;
}

TEST(ProjectMessages, CommandLayoutIsByteExact) {
  FcCommand command;
  command.seq = 0x01020304;
  command.command = FcCommand::kTakeoff;
  command.target_W_m = {0.0f, 0.0f, 10.0f};
  command.speed_limit_mps = -1.0f;
  command.yaw_deg = std::numeric_limits<float>::quiet_NaN();
  Payload payload;
  ASSERT_TRUE(encode_payload(command, payload).ok());
  std::vector<uint8_t> expected = {0x04, 0x03, 0x02, 0x01, 3};
  for (float v : {0.0f, 0.0f, 10.0f, -1.0f}) {
    const auto b = le_bytes(std::bit_cast<uint32_t>(v));
    expected.insert(expected.end(), b.begin(), b.end());
  }
  const auto nan = le_bytes(std::bit_cast<uint32_t>(std::numeric_limits<float>::quiet_NaN()));
  expected.insert(expected.end(), nan.begin(), nan.end());
  ASSERT_EQ(payload.size, 25u);
  EXPECT_EQ(std::vector<uint8_t>(payload.bytes.begin(), payload.bytes.begin() + 25), expected);
  EXPECT_EQ(transfer_frame_count(payload.size), 4u);
}

TEST(ProjectMessages, StatusPacksModeArmedFailsafeIntoTheFirstByte) {
  FcStatus status;
  status.mode = FcStatus::kModeGoto;           // 011
  status.armed = true;                          // 1
  status.failsafe = FcStatus::kFailsafeLowBattery;  // 0010
  status.last_command_seq = -1;
  status.last_command_accepted = true;
  status.last_command_reason = FcStatus::kReasonBusy;  // 13 = 0001101
  Payload payload;
  ASSERT_TRUE(encode_payload(status, payload).ok());
  ASSERT_EQ(payload.size, 34u);
  EXPECT_EQ(payload.bytes[0], 0x72);
  // Bytes 1..28: six float32 and two float16 (zeros here); then seq -1 and the last byte.
  for (int i = 29; i < 33; ++i) EXPECT_EQ(payload.bytes[i], 0xFF) << i;
  EXPECT_EQ(payload.bytes[33], 0x80 | 13) << "accepted bit, then uint7 reason";
}

TEST(ProjectMessages, ReasonTextsRoundTrip) {
  for (uint8_t reason = 0; reason <= FcStatus::kLastReason; ++reason) {
    uint8_t back = 255;
    ASSERT_TRUE(fc_reason_from_text(fc_reason_text(reason), back)) << int(reason);
    EXPECT_EQ(back, reason);
  }
  EXPECT_EQ(fc_reason_text(FcStatus::kReasonNone), "");
  uint8_t ignored = 0;
  EXPECT_FALSE(fc_reason_from_text("no such reason", ignored));
}

TEST(Casts, SaturationAndTruncation) {
  EscRawCommand esc;
  esc.cmd = {9000, -9000};
  EscStatus status;
  status.power_rating_pct = 200;  // uint7
  status.esc_index = 40;          // uint5
  status.voltage = 1e6f;          // beyond float16
  status.current = -std::numeric_limits<float>::infinity();
  status.rpm = 1 << 20;           // int18
  Timestamp ts;
  ts.usec = (uint64_t{1} << 56) + 5;  // truncated uint56

  Payload payload;
  EscRawCommand esc_back;
  ASSERT_TRUE(encode_payload(esc, payload).ok());
  ASSERT_TRUE(decode_payload(payload.data(), payload.size, esc_back).ok());
  EXPECT_EQ(esc_back.cmd[0], 8191);
  EXPECT_EQ(esc_back.cmd[1], -8192);

  EscStatus status_back;
  ASSERT_TRUE(encode_payload(status, payload).ok());
  ASSERT_TRUE(decode_payload(payload.data(), payload.size, status_back).ok());
  EXPECT_EQ(status_back.power_rating_pct, 127);
  EXPECT_EQ(status_back.esc_index, 31);
  EXPECT_EQ(status_back.voltage, 65504.0f) << "finite values saturate to the float16 maximum";
  EXPECT_TRUE(std::isinf(status_back.current) && status_back.current < 0) << "infinity stays";
  EXPECT_EQ(status_back.rpm, (1 << 17) - 1);

  Timestamp ts_back;
  ASSERT_TRUE(encode_payload(ts, payload).ok());
  ASSERT_TRUE(decode_payload(payload.data(), payload.size, ts_back).ok());
  EXPECT_EQ(ts_back.usec, 5u);
}

TEST(TailArrayOptimisation, EmptyAndFullTailArrays) {
  Payload payload;
  EscRawCommand none;
  ASSERT_TRUE(encode_payload(none, payload).ok());
  EXPECT_EQ(payload.size, 0u) << "no length prefix: an empty tail array is no bytes at all";
  std::vector<CanFrame> frames;
  append_transfer_frames(message_header<EscRawCommand>(10, 0), EscRawCommand::kType.signature,
                         payload.data(), payload.size, frames);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].size, 1u) << "just the tail byte";

  EscRawCommand full;
  for (int i = 0; i < 20; ++i) full.cmd.push_back(static_cast<int16_t>(i * 100 - 1000));
  ASSERT_TRUE(encode_payload(full, payload).ok());
  EXPECT_EQ(payload.size, 35u) << "20 x 14 bits, no prefix";
  EscRawCommand back;
  ASSERT_TRUE(decode_payload(payload.data(), payload.size, back).ok());
  EXPECT_EQ(back, full);
}

TEST(DecodeErrors, NameTheFieldAndTheProblem) {
  StaticPressure pressure;
  CodecStatus status = decode_payload(std::vector<uint8_t>{1, 2, 3, 4, 5}.data(), 5, pressure);
  EXPECT_EQ(status.code, CodecStatus::Code::kPayloadTooShort);
  EXPECT_EQ(status.message(StaticPressure::kType.full_name),
            "uavcan.equipment.air_data.StaticPressure: payload ends inside field "
            "'static_pressure_variance'");

  const std::vector<uint8_t> long_payload(8, 0);
  status = decode_payload(long_payload.data(), long_payload.size(), pressure);
  EXPECT_EQ(status.code, CodecStatus::Code::kTrailingBytes);
  EXPECT_NE(status.message("x").find("2 byte(s) after the last field"), std::string::npos);

  // Fix2.covariance is not the last field: it has a 6-bit length prefix; say 37 (> 36).
  GnssFix2 fix;
  Payload payload;
  ASSERT_TRUE(encode_payload(fix, payload).ok());
  // The prefix starts at bit 378 = byte 47, bit 2: the low six bits of byte 47.
  payload.bytes[47] = static_cast<uint8_t>((payload.bytes[47] & 0xC0) | 37);
  status = decode_payload(payload.data(), payload.size, fix);
  EXPECT_EQ(status.code, CodecStatus::Code::kArrayTooLong);
  EXPECT_EQ(status.message(GnssFix2::kType.full_name),
            "uavcan.equipment.gnss.Fix2: field 'covariance' has 37 elements, at most 36");

  // A tail array longer than its bound: 16 actuator commands of 4 bytes.
  const std::vector<uint8_t> sixteen(16 * 4, 0);
  ActuatorArrayCommand array;
  status = decode_payload(sixteen.data(), sixteen.size(), array);
  EXPECT_EQ(status.code, CodecStatus::Code::kArrayTooLong);
  EXPECT_STREQ(status.field, "commands");
}

TEST(JsonErrors, NameThePath) {
  auto error_of = [](const nlohmann::json& j) -> std::string {
    try {
      message_from_json<GnssFix2>(j);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  nlohmann::json fix = message_to_json(sample(static_cast<GnssFix2*>(nullptr)));
  EXPECT_EQ(error_of(fix), "");
  auto missing = fix;
  missing.erase("pdop");
  EXPECT_EQ(error_of(missing), "pdop: missing");
  auto unknown = fix;
  unknown["speed"] = 3;
  EXPECT_EQ(error_of(unknown), "speed: not a field of uavcan.equipment.gnss.Fix2");
  auto out_of_range = fix;
  out_of_range["sats_used"] = 64;
  EXPECT_EQ(error_of(out_of_range), "sats_used: 64 is outside uint6");
  auto nested = fix;
  nested["ecef_position_velocity"][0]["position_xyz_mm"][1] = "far";
  EXPECT_EQ(error_of(nested),
            "ecef_position_velocity[0].position_xyz_mm[1]: expected an integer (int36), got \"far\"");
  auto too_many = fix;
  too_many["covariance"] = std::vector<double>(37, 1.0);
  EXPECT_EQ(error_of(too_many), "covariance: 37 elements, at most 36");
}

}  // namespace
}  // namespace a3::bridge
