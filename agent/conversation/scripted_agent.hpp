// The scripted agent: our reference policy, a competent operator written as rules. From the
// mission it plans a short sequence of turns — pre-flight checks (telemetry, geofence,
// weather, a route around no-fly zones from the ground station, a collision-avoidance
// exchange with conflicting traffic), take-off and the objectives' legs (surveys as onboard
// lawnmowers, image points, deliveries), return and landing — and adapts every turn to the
// network: on a hard link it asks for URLLC for control and keeps images on board until the
// link is good again, then hands them over. When the supervisor reports traffic close by, it
// asks the swarm for separation (A2A collision_avoidance) before anything else. A capture at an
// image point waits until telemetry shows the vehicle there (a supervisor's turn about a
// degraded link can come while it is still on the way).
#pragma once

#include <Eigen/Core>

#include <deque>
#include <string>
#include <vector>

#include "agent/conversation/agent.hpp"

namespace a3::agent {

class ScriptedAgent final : public Agent {
 public:
  ScriptedAgent() = default;
  std::string name() const override { return "scripted"; }
  AgentDecision decide(const AgentContext& context) override;

 private:
  struct Step {
    std::string intent;
    std::string text;
    std::vector<nlohmann::json> actions;
    // A step done at a place (capturing an image point): it waits until the latest telemetry
    // puts the vehicle within arrive_within_m of it (horizontally).
    bool needs_arrival = false;
    Eigen::Vector2d at = Eigen::Vector2d::Zero();
    double arrive_within_m = 0.0;
  };
  void plan(const AgentContext& context);
  std::vector<nlohmann::json> route_from_path_plan(const AgentContext& context) const;
  bool still_flying_a_route(const AgentContext& context) const;
  // True when telemetry read after the last motion leg was issued shows that leg finished (no
  // leg issued: true). A supervisor's turn in between (a degraded link, a status request
  // without telemetry) is not evidence that the vehicle got there.
  bool last_leg_done(const AgentContext& context) const;
  static bool arrived(const AgentContext& context, const Step& step);

  bool planned_ = false;
  std::deque<Step> steps_;
  bool images_held_ = false;  // captures kept on board while the link was poor
  bool detour_flown_ = false;  // the ground station's route has been used
  int leg_turn_index_ = -1;   // dialogue index of the turn that issued the last motion leg
};

// The SPEC §2 "hard" test on an n_t object.
bool is_hard_network(const nlohmann::json& net);

}  // namespace a3::agent
