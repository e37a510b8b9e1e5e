// The simulated supervisor: speaks every other turn, from templates filled from the scenario
// and reacting to what is happening (it watches the mission's ground truth: objectives done,
// the flight mode, the network, traffic nearby). It confirms the plan, acknowledges progress,
// reports degradations and traffic, asks for status (sometimes with a telemetry read), and
// closes the mission once the vehicle has landed.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "agent/conversation/turn.hpp"
#include "agent/mission/mission.hpp"

namespace a3::agent {

struct SupervisorView {
  const Mission* mission = nullptr;
  nlohmann::json progress;          // MissionTracker::to_json()
  nlohmann::json net;               // n_t now
  bool network_degraded = false;    // hard now, and was not at the previous user turn
  std::string traffic_alert;        // e.g. "peer-1 at 85 m" ("" when none is close)
  bool landed_after_flight = false;
  int turn_number = 0;
  int max_turns = 12;
  int objectives_newly_done = 0;
  std::string newly_done_names;
};

struct UserUtterance {
  std::string intent;
  std::string text;
  nlohmann::json actions = nlohmann::json::array();
};

class SimulatedUser {
 public:
  UserUtterance speak(const SupervisorView& view);

 private:
  int turns_spoken_ = 0;
  int status_requests_ = 0;
};

}  // namespace a3::agent
