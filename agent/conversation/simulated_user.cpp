// The supervisor's templates.
#include "agent/conversation/simulated_user.hpp"

#include <cstdio>

namespace a3::agent {
namespace {

// " Not done: id (why); id (why)." for the objectives the judge can say why of ("" if none).
std::string why_not_done_text(const nlohmann::json& progress) {
  std::string reasons;
  for (const auto& o : progress.value("objectives", nlohmann::json::array())) {
    if (!o.contains("why_not")) continue;
    reasons += (reasons.empty() ? "" : "; ") + o.value("id", std::string("?")) + " (" + o.value("why_not", "") + ")";
  }
  return reasons.empty() ? "" : " Not done: " + reasons + ".";
}

}  // namespace

UserUtterance SimulatedUser::speak(const SupervisorView& v) {
  ++turns_spoken_;
  UserUtterance u;
  char text[1200];
  if (turns_spoken_ == 1) {
    u.intent = "confirm_mission_start";
    std::snprintf(text, sizeof text, "Pre-flight checks received. Proceed with the mission: %s",
                  v.mission != nullptr ? v.mission->description.c_str() : "");
  } else if (v.landed_after_flight) {
    u.intent = "acknowledge_landing";
    std::snprintf(text, sizeof text, "Landing confirmed. %s%s",
                  v.progress.value("all_done", false) ? "All objectives met, mission complete." : "Mission closed.",
                  why_not_done_text(v.progress).c_str());
  } else if (!v.traffic_alert.empty()) {
    u.intent = "traffic_alert";
    std::snprintf(text, sizeof text, "Traffic alert: %s. Keep separation.", v.traffic_alert.c_str());
  } else if (v.network_degraded) {
    u.intent = "report_network_issue";
    std::snprintf(text, sizeof text, "The link is degrading on %s: %.0f ms latency, %.1f %% loss, %.1f Mbps. Adapt.",
                  v.net.value("slice", "?").c_str(), v.net.value("lat_ms", 0.0), v.net.value("loss_pct", 0.0),
                  v.net.value("throughput_mbps", 0.0));
  } else if (v.objectives_newly_done > 0) {
    u.intent = "acknowledge_progress";
    std::snprintf(text, sizeof text, "Confirmed: %s done. Continue.", v.newly_done_names.c_str());
  } else {
    u.intent = "request_status";
    std::snprintf(text, sizeof text, "Status report, please.%s", why_not_done_text(v.progress).c_str());
    // Every other status request, the supervisor reads the telemetry itself.
    if (status_requests_++ % 2 == 0) {
      u.actions.push_back({{"type", "mcp"}, {"name", "read_telemetry"}, {"args", nlohmann::json::object()}});
    }
  }
  u.text = text;
  return u;
}

}  // namespace a3::agent
