// The flight controller's command and status on their three sides: the LCM messages the rest
// of the rig speaks (fc_command_t on A3_FC_CMD, fc_status_t on A3_FC_STATUS), their CAN forms
// (a3.fc.Command, a3.fc.Status) and the flight controller's own types (FlightCommand,
// FlightStatus). Codes are equal on all sides; only units of storage change (double on LCM,
// float32/float16 on CAN) and the refusal reason, a code on CAN, becomes its text on LCM.
#pragma once

#include <cstdint>

#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "bridge/dronecan/msg/a3_fc.hpp"
#include "bridge/fc/flight_controller.hpp"

namespace a3::bridge {

// double → float32 without undefined behaviour: out-of-range values become ±inf, NaN stays NaN.
float to_float32(double value);

// The bridge's direction: A3_FC_CMD → a3.fc.Command. Command codes pass unchanged (a negative
// int8 becomes a large uint8 the fc refuses as an unknown command).
FcCommand fc_command_to_can(const a3lcm::fc_command_t& command);
// True when a command carries a non-finite target or speed (a NaN yaw means "keep": fine).
bool fc_command_has_nonfinite(const a3lcm::fc_command_t& command);

// The fc's direction: a3.fc.Command → what FlightController::on_command takes.
FlightCommand flight_command_from_can(const FcCommand& command);
// FlightController status → a3.fc.Status.
FcStatus fc_status_to_can(const FlightStatus& status);

// The bridge's direction: a3.fc.Status → A3_FC_STATUS, stamped with the bridge's receive time.
a3lcm::fc_status_t fc_status_from_can(const FcStatus& status, int64_t utime_us);

}  // namespace a3::bridge
