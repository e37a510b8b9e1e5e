// The scripted agent: our reference policy, a competent operator written as rules. From the
// mission it plans one leg per objective (surveys as onboard lawnmowers, image points as a
// flight to the point and a capture there, deliveries as a flight and a descent to drop
// height), flies them in order after pre-flight checks (telemetry, geofence, weather, a route
// around no-fly zones from the ground station — flown with the leg's own altitudes and
// descent — and the swarm's traffic), then returns and lands. Each turn it judges the last leg
// from evidence: telemetry read after the leg was sent (at rest in hold at the commanded
// point and altitude, within the objective's own radius), the supervisor's acknowledgement of
// the objective, or the supervisor's status request (it asks only once the vehicle has come to
// rest). A capture needs that evidence; a leg whose command was lost, or that came to rest
// elsewhere, is sent again; a leg the gate refused gets a route from the ground station (a
// pattern behind a no-fly zone: a transit along the route first), and is given up after three
// sends; without evidence it checks telemetry while the turn budget has turns to spare. A
// capture answered timeout or error (lost on the link, a sensor not active) is not claimed: the
// leg is flown back and captured again, once, when the budget has the two turns it takes. A
// take-off answered timeout or error is sent again with the next leg unless telemetry since shows
// the vehicle armed in the air; a leg refused for want of a sensor whose activation was lost is
// sent again with the activation. Turn budgeting folds only what can be done at once: a capture with the next
// leg (capture first, then move on), the last capture with the return, and — when the
// budget is short — the pre-flight with the launch; never a leg with the capture at its end.
// It adapts every turn to the network: on a hard link it asks for URLLC and keeps images on
// board until the link is good again, then hands them over. When the supervisor reports
// traffic close by, it asks the swarm for separation (A2A collision_avoidance) first; with
// other aircraft about, it also asks in every turn from the launch to the landing (after any
// motion, so the swarm predicts along the new route), so a conflict is negotiated before the
// supervisor's alert, which may come seconds before it or in the dialogue's last turn.
// Its state is a function of the dialogue it is shown, so replaying the dialogue rebuilds it.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "agent/conversation/agent.hpp"

namespace a3::agent {

class ScriptedAgent final : public Agent {
 public:
  ScriptedAgent() = default;
  std::string name() const override { return "scripted"; }
  AgentDecision decide(const AgentContext& context) override;

  // One objective's work: a motion (with its set-up) and, for an image point, a capture at its end.
  struct Leg {
    std::string objective_id;
    std::string intent, text;
    std::vector<nlohmann::json> actions;  // sensor set-up, then the motion
    Eigen::Vector3d end_W_m = Eigen::Vector3d::Zero();  // where the motion ends (commanded)
    bool ends_at_point = true;  // false: a pattern (survey) that ends wherever its last line ends
    double radius_m = 0.0;      // the objective's own radius: how close counts
    bool capture = false;
    std::vector<nlohmann::json> capture_actions;
    std::string capture_intent, capture_text;
    // Where the motion starts its work (its first point): routes around no-fly zones end here.
    Eigen::Vector3d anchor_W_m = Eigen::Vector3d::Zero();
    bool transit_planned = false;  // a pattern leg: a transit along a route has been put before it
    bool is_route = false;         // a transit: its motion is a route already
    int sends = 0;                 // times its motion has been sent
    int captures = 0;              // times its capture has been sent
  };
  // Where the last leg stands, from the evidence in the dialogue.
  enum class LegStatus { kDone, kFlying, kLost, kRefused, kUnknown };

 private:
  struct Choice {
    std::string intent, text;
    std::vector<nlohmann::json> actions;
  };
  void plan(const AgentContext& context);
  Choice next_choice(const AgentContext& context);
  Choice preflight_choice(const AgentContext& context);
  Choice after_leg_done(const AgentContext& context, int agent_turns_left);
  void add_leg_motion(const AgentContext& context, Choice* choice);
  void add_return(const AgentContext& context, Choice* choice);
  // Agent turns the rest of the plan needs at least, from the current leg on (pre-flight
  // excluded), with one check on the way for every leg sent right after a capture.
  int turns_needed_after_preflight() const;
  // The leg's motion along the ground station's route to its anchor, if it gave one; else empty.
  std::vector<nlohmann::json> route_for(const AgentContext& context, const Leg& leg, const nlohmann::json& motion) const;
  void put_transit_before_pattern(const AgentContext& context);
  Choice after_refusal(const AgentContext& context, int agent_turns_left);
  // A capture answered timeout or error (the link lost it, or the sensor was not active): the
  // leg is flown again and captured again, once; nothing when the last capture stands.
  std::optional<Choice> retake_failed_capture(const AgentContext& context, int agent_turns_left);
  std::vector<nlohmann::json> adapt_to_network(const AgentContext& context, std::vector<nlohmann::json> actions);

  bool planned_ = false;
  Choice preflight_;
  std::vector<Leg> legs_;
  std::size_t leg_ = 0;          // the current leg
  bool preflight_done_ = false;
  bool launched_ = false;
  bool leg_sent_ = false;        // the current leg's motion has been sent
  bool returned_ = false;        // return_to_home has been sent
  bool images_held_ = false;     // captures kept on board while the link was poor
  int leg_turn_index_ = -1;      // dialogue index of the turn that sent the current leg
  int launch_turn_index_ = -1;   // dialogue index of the turn that sent the take-off
  int return_turn_index_ = -1;   // dialogue index of the turn that sent return_to_home
  int capture_turn_index_ = -1;  // dialogue index of the turn that sent the last capture
  std::size_t captured_leg_ = 0; // the leg it captured
  std::vector<std::string> given_up_;  // objectives it gave up (refused again and again, a failed capture)
};

// The SPEC §2 "hard" test on an n_t object.
bool is_hard_network(const nlohmann::json& net);

// The status of a leg sent in the turn at dialogue index leg_turn_index, from the turns after it.
ScriptedAgent::LegStatus leg_status(const AgentContext& context, const ScriptedAgent::Leg& leg, int leg_turn_index);

}  // namespace a3::agent
