// Refused CAN traffic as safety events.
#include "bridge/sim/refusal_events.hpp"

#include <array>

#include "bridge/dronecan/messages.hpp"

namespace a3::bridge {
namespace {

std::string command_text(uint8_t command) {
  static constexpr std::array<const char*, FcCommand::kLastCommand + 1> kNames = {
      "heartbeat", "arm", "disarm", "takeoff", "hold", "go-to", "land", "return home", "emergency stop", "set speed"};
  return command < kNames.size() ? kNames[command] : "unknown command " + std::to_string(command);
}

std::string counts_text(uint64_t in_report, uint64_t total) {
  return std::to_string(in_report) + " refused since the last report, " + std::to_string(total) + " in all";
}

a3lcm::safety_event_t event_at(int64_t utime_us, const std::array<double, 3>& p_W_m, const char* source) {
  a3lcm::safety_event_t e{};
  e.utime_us = utime_us;
  e.kind = kCommandRefusedKind;
  e.source = source;
  for (int i = 0; i < 3; ++i) e.p_W_m[i] = p_W_m[i];
  return e;
}

}  // namespace

std::string data_type_text(uint16_t data_type_id) {
  std::string name;
  std::apply([&](auto... type) {
    ((type.kType.default_dtid == data_type_id ? (void)(name = type.kType.full_name) : (void)0), ...);
  }, MessageTypes{});
  return name.empty() ? "data type " + std::to_string(data_type_id) : name;
}

a3lcm::safety_event_t safety_event_from_fc_refusal(const FcCommandRefused& r, int64_t utime_us,
                                                   const std::array<double, 3>& p_W_m) {
  a3lcm::safety_event_t e = event_at(utime_us, p_W_m, "fc");
  e.value = r.refused_in_report;
  std::string what = data_type_text(r.data_type_id);
  if (r.data_type_id == FcCommand::kType.default_dtid) {
    what += " " + std::to_string(r.command) + " (" + command_text(r.command) + ", seq " + std::to_string(r.seq) + ")";
  }
  e.detail = "the fc refused " + what + " from CAN node " + std::to_string(r.source_node_id) +
             ": not one of its command sources; " + counts_text(r.refused_in_report, r.refused_total);
  return e;
}

a3lcm::safety_event_t safety_event_from_foreign_fc_traffic(const ForeignFcTraffic& r, int64_t utime_us,
                                                           const std::array<double, 3>& p_W_m) {
  a3lcm::safety_event_t e = event_at(utime_us, p_W_m, "bridge");
  e.value = static_cast<double>(r.refused_in_report);
  e.detail = "the bridge refused " + data_type_text(r.data_type_id) + " from CAN node " +
             std::to_string(r.source_node_id) + ": only the fc (node " + std::to_string(r.fc_node_id) +
             ") drives the ESCs and reports the flight state; " + counts_text(r.refused_in_report, r.refused_total);
  return e;
}

}  // namespace a3::bridge
