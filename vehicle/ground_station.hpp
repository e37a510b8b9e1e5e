// The simulated ground_station:
//   - path_plan {start?: [x, y(, z)], goal: [x, y(, z)], z?}: a route around the no-fly zones
//     (path_planner.hpp) that passes the gate's geometric checks, at altitude z (else the
//     goal's z, else the start's altitude kept inside the envelope — from the ground, the
//     return altitude); start defaults to the vehicle's position. A goal [x, y, z] with z given
//     too keeps the route at z and ends with the climb or descent to the goal's own z over it.
//     Status "failed" with the reason when there is none.
//   - handover_data {items?: [id | {"id"} ...]}: acknowledges the images it receives; those
//     still on board only (store_only captures, survey images) now cross the downlink, so the
//     answer carries their bytes. Without items: every image not yet downlinked.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>

#include "vehicle/image_store.hpp"
#include "vehicle/path_planner.hpp"
#include "vehicle/peer_answer.hpp"
#include "vehicle/safety_gate.hpp"

namespace a3::vehicle {

class GroundStation {
 public:
  // The gate must outlive the ground station.
  GroundStation(const SafetyGate& gate, PlannerConfig config);

  // position_W_m: the vehicle's position as the ground knows it (the fc's estimate), if any.
  PeerAnswer path_plan(const std::optional<Eigen::Vector3d>& position_W_m, const nlohmann::json& payload) const;
  PeerAnswer handover_data(ImageStore& images, const nlohmann::json& payload) const;

 private:
  const SafetyGate& gate_;
  PlannerConfig config_;
};

}  // namespace a3::vehicle
