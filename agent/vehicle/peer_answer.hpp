// What a simulated A2A peer answers, in the corpus shape {"task", "from", "status", "payload"},
// and what a peer may know of our vehicle: the rig's true state and the path it is about to fly.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "agent/airspace.hpp"

namespace a3::agent {

struct PeerAnswer {
  std::string status = "ok";  // "ok" | "error" | "failed" | ...
  nlohmann::json payload = nlohmann::json::object();
  int64_t extra_bytes = 0;    // data the answer carries down the link (handed-over images)
};

struct SelfView {
  double now_s = 0.0;
  bool known = false;                               // a state has been seen
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();  // true position
  Eigen::Vector3d v_W_mps = Eigen::Vector3d::Zero();
  TrafficPlan predicted;  // where the vehicle will be from now_s on (holding at its end)
};

nlohmann::json a2a_observation(const std::string& task, const std::string& from, const PeerAnswer& answer);

}  // namespace a3::agent
