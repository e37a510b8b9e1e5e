// The project's flight-controller messages a3.fc.Command (20600) and a3.fc.Status (20601):
// the CAN forms of the LCM messages fc_command_t and fc_status_t. Their DSDL is
// bridge/dsdl/a3/fc/*.uavcan; a test derives these signatures from those files.
// Data type IDs sit in DroneCAN's vendor-specific message range (20000-21000), away from
// the IDs public vendor namespaces use (ArduPilot's 20000-20010 and 20790, for instance).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "bridge/dronecan/dsdl_types.hpp"

namespace a3::bridge {

struct FcCommand {
  static constexpr DataTypeInfo kType{"a3.fc.Command", 20600, 0xc7e0e1909c5690acULL, 200};
  // The same codes as fc_command_t's constants.
  static constexpr uint8_t kHeartbeat = 0, kArm = 1, kDisarm = 2, kTakeoff = 3, kHold = 4,
                           kGoto = 5, kLand = 6, kReturnHome = 7, kEmergencyStop = 8,
                           kSetSpeed = 9;
  static constexpr uint8_t kLastCommand = kSetSpeed;
  int32_t seq = 0;
  uint8_t command = kHeartbeat;
  std::array<float, 3> target_W_m{};  // ENU, m; TAKEOFF uses [2] as altitude
  float speed_limit_mps = 0;           // <= 0: keep the current limit
  float yaw_deg = 0;                   // ENU degrees; NaN: keep

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.seq, "seq", dsdl::Int{32});
    v(self.command, "command", dsdl::Uint{8});
    v(self.target_W_m, "target_W_m", dsdl::Array{dsdl::Float{32}});
    v(self.speed_limit_mps, "speed_limit_mps", dsdl::Float{32});
    v(self.yaw_deg, "yaw_deg", dsdl::Float{32});
  }
  bool operator==(const FcCommand&) const = default;
};

struct FcStatus {
  static constexpr DataTypeInfo kType{"a3.fc.Status", 20601, 0x9c0901d7ce256c8fULL, 272};
  // The same codes as fc_status_t's constants.
  static constexpr uint8_t kModeDisarmed = 0, kModeTakeoff = 1, kModeHold = 2, kModeGoto = 3,
                           kModeLand = 4, kModeReturnHome = 5, kModeEmergency = 6;
  static constexpr uint8_t kFailsafeNone = 0, kFailsafeLinkLoss = 1, kFailsafeLowBattery = 2,
                           kFailsafeGeofence = 3, kFailsafeAltitude = 4;
  enum Reason : uint8_t {
    kReasonNone = 0,
    kReasonUnknownCommand = 1,
    kReasonInvalidArgument = 2,
    kReasonNotArmed = 3,
    kReasonInFlight = 4,
    kReasonOnGround = 5,
    kReasonOutsideGeofence = 6,
    kReasonAboveAltitudeLimit = 7,
    kReasonBelowAltitudeLimit = 8,
    kReasonNoPositionEstimate = 9,
    kReasonLowBattery = 10,
    kReasonFailsafeActive = 11,
    kReasonEmergencyStopped = 12,
    kReasonBusy = 13,
  };
  static constexpr uint8_t kLastReason = kReasonBusy;

  uint8_t mode = kModeDisarmed;  // uint3
  bool armed = false;
  uint8_t failsafe = kFailsafeNone;  // uint4
  std::array<float, 3> p_W_m{};      // ENU, m, float32
  std::array<float, 3> v_W_mps{};    // ENU, m/s, float32
  float yaw_deg = 0;                 // ENU degrees, float16
  float battery_pct = 0;             // float16
  int32_t last_command_seq = 0;
  bool last_command_accepted = false;
  uint8_t last_command_reason = kReasonNone;  // uint7, a Reason

  template <class Self, class V>
  static void visit_fields(Self& self, V& v) {
    v(self.mode, "mode", dsdl::Uint{3});
    v(self.armed, "armed", dsdl::Bool{});
    v(self.failsafe, "failsafe", dsdl::Uint{4});
    v(self.p_W_m, "p_W_m", dsdl::Array{dsdl::Float{32}});
    v(self.v_W_mps, "v_W_mps", dsdl::Array{dsdl::Float{32}});
    v(self.yaw_deg, "yaw_deg", dsdl::Float{16});
    v(self.battery_pct, "battery_pct", dsdl::Float{16});
    v(self.last_command_seq, "last_command_seq", dsdl::Int{32});
    v(self.last_command_accepted, "last_command_accepted", dsdl::Bool{});
    v(self.last_command_reason, "last_command_reason", dsdl::Uint{7});
  }
  bool operator==(const FcStatus&) const = default;
};

// Text of a refusal reason, the words fc_status_t.last_command_reason carries
// ("" for kReasonNone, "reason code N" for codes not known here).
std::string_view fc_reason_text(uint8_t reason);
// The reason code of such a text; false when the text is none of them.
bool fc_reason_from_text(std::string_view text, uint8_t& reason);

}  // namespace a3::bridge
