// Refused CAN traffic as safety events (safety_event_t on A3_SAFETY, kind "command_refused"):
// the fc's reports (a3.fc.CommandRefused: commands from a node that is not a command source),
// which the bridge publishes for the fc (the fc never uses LCM), and the bridge's own refusals
// of flight-controller traffic (esc.RawCommand, a3.fc.Status) from a node that is not the fc.
// value = the refusals the event covers (they are rate-limited at their source).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "a3lcm/safety_event_t.hpp"
#include "bridge/dronecan/msg/a3_fc_refusal.hpp"

namespace a3::bridge {

inline constexpr const char* kCommandRefusedKind = "command_refused";

// "a3.fc.Command", "esc.RawCommand", ... for the rig's types; "data type N" for others.
std::string data_type_text(uint16_t data_type_id);

a3lcm::safety_event_t safety_event_from_fc_refusal(const FcCommandRefused& report, int64_t utime_us,
                                                   const std::array<double, 3>& p_W_m);

struct ForeignFcTraffic {
  uint8_t source_node_id = 0;
  uint16_t data_type_id = 0;
  uint8_t fc_node_id = 0;
  uint64_t refused_in_report = 0;
  uint64_t refused_total = 0;
};
a3lcm::safety_event_t safety_event_from_foreign_fc_traffic(const ForeignFcTraffic& refused, int64_t utime_us,
                                                           const std::array<double, 3>& p_W_m);

}  // namespace a3::bridge
