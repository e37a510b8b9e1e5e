// Reason texts of a3.fc.Status (see a3_fc.hpp).
#include "bridge/dronecan/msg/a3_fc.hpp"

#include <array>

namespace a3::bridge {
namespace {

constexpr std::array<std::string_view, FcStatus::kLastReason + 1> kReasonTexts = {
    "",
    "unknown command",
    "invalid argument",
    "not armed",
    "not allowed in flight",
    "not allowed on the ground",
    "outside the geofence",
    "above the altitude limit",
    "below the altitude limit",
    "no position estimate",
    "battery too low",
    "a failsafe is active",
    "emergency stopped",
    "not allowed in the current mode",
};

}  // namespace

std::string_view fc_reason_text(uint8_t reason) {
  if (reason < kReasonTexts.size()) return kReasonTexts[reason];
  return "unknown reason code";
}

bool fc_reason_from_text(std::string_view text, uint8_t& reason) {
  for (std::size_t i = 0; i < kReasonTexts.size(); ++i) {
    if (kReasonTexts[i] == text) {
      reason = static_cast<uint8_t>(i);
      return true;
    }
  }
  return false;
}

}  // namespace a3::bridge
