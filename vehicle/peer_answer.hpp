// What a simulated A2A peer answers, in the corpus shape {"task", "from", "status", "payload"},
// and what a peer may know of our vehicle: the rig's true state and the path it is about to fly.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "vehicle/ground_shared.hpp"

namespace a3::vehicle {

struct PeerAnswer {
  std::string status = "ok";  // "ok" | "error" | "failed" | ...
  nlohmann::json payload = nlohmann::json::object();
  int64_t extra_bytes = 0;    // data the answer carries down the link (handed-over images)
};

// What a prediction of our own track rests on: the onboard route, the take-off climb, the fc's
// return home or landing, holding still (on the ground too), or straight on at the velocity
// (the fc flies somewhere the tool server did not send it).
enum class TrackBasis { kRoute, kTakeoff, kReturnHome, kLand, kHold, kVelocity };

// "route", "takeoff", "return_home", "land", "hold", "velocity".
inline const char* track_basis_name(TrackBasis basis) {
  switch (basis) {
    case TrackBasis::kRoute: return "route";
    case TrackBasis::kTakeoff: return "takeoff";
    case TrackBasis::kReturnHome: return "return_home";
    case TrackBasis::kLand: return "land";
    case TrackBasis::kHold: return "hold";
    case TrackBasis::kVelocity: return "velocity";
  }
  return "hold";
}

struct SelfView {
  double now_s = 0.0;
  bool known = false;                               // a state has been seen
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();  // true position
  Eigen::Vector3d v_W_mps = Eigen::Vector3d::Zero();
  TrafficPlan predicted;  // where the vehicle will be from now_s on (holding at its end)
  // What the prediction rests on, and the speed its horizontal legs were commanded at (their
  // timing is the ground speed made good at it).
  TrackBasis basis = TrackBasis::kHold;
  double commanded_speed_mps = 0.0;
};

nlohmann::json a2a_observation(const std::string& task, const std::string& from, const PeerAnswer& answer);

}  // namespace a3::vehicle
