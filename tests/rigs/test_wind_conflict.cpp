// Issue 15 as a whole episode: a 7 m/s headwind halves the ground speed the vehicle makes good,
// so a patrol crossing its track, which the commanded 9 m/s would pass half a minute early,
// meets it at the crossing. The vehicle's collision_avoidance prediction (own track at the
// ground speed made good in the estimated wind) must call that conflict, and say which ground
// speed and wind it assumed; without avoidance the breach then happens, with the patrol asked to
// yield it does not.
// Scenario: tests/data/scenarios/headwind-crossing.json (75 s of mission per episode).
#include <gtest/gtest.h>

#include <memory>

#include "agent/conversation/agent.hpp"
#include "tests/rigs/rig_test_support.hpp"
#include "vehicle/swarm_peer.hpp"

namespace a3::rigs {
namespace {

using nlohmann::json;

const Eigen::Vector3d kHome_W_m(100, 300, 0), kMast_W_m(400, 300, 20);
constexpr double kCommanded_mps = 9.0;

// Takes off, flies to the mast at 9 m/s and asks the swarm about conflicts in its first turn
// (request "query": only report; "yield": make a conflicting peer climb away); then watches.
class HeadwindAgent final : public agent::Agent {
 public:
  explicit HeadwindAgent(std::string request) : request_(std::move(request)) {}
  std::string name() const override { return "headwind-test"; }
  agent::AgentDecision decide(const agent::AgentContext& context) override {
    agent::AgentDecision d;
    if (context.turn_number == 3) {  // in flight: the same route again, to read the wind it now assumes
      d.intent = "navigate_to_target";
      d.text = "Flying on to the mast.";
      d.actions = json::array({navigate_to_mast()});
      return d;
    }
    if (context.turn_number > 1) {
      d.intent = "monitor";
      d.text = "Flying on.";
      return d;
    }
    d.intent = "navigate_to_target";
    d.text = "Taking off for the mast, checking the traffic.";
    d.actions = json::array(
        {{{"type", "mcp"}, {"name", "takeoff"}, {"args", {{"altitude_m", kMast_W_m.z()}}}},
         navigate_to_mast(),
         {{"type", "a2a"}, {"task", "collision_avoidance"}, {"to", "uav_swarm_agent"}, {"payload", {{"request", request_}}}}});
    return d;
  }

 private:
  static json navigate_to_mast() {
    return {{"type", "mcp"},
            {"name", "navigate_to"},
            {"args", {{"waypoints", {{kMast_W_m.x(), kMast_W_m.y(), kMast_W_m.z()}}}, {"speed_mps", kCommanded_mps}}}};
  }

  std::string request_;
};

RunResult fly(const std::string& request) {
  RunOptions o = a3::test::virtual_run(std::string(A3_SOURCE_DIR) + "/tests/data/scenarios/headwind-crossing.json",
                                       "wind-conflict-" + request);
  o.agent_factory = [request] { return std::make_unique<HeadwindAgent>(request); };
  RunResult r = a3::test::run(o);
  std::filesystem::remove_all(o.out_dir);
  return r;
}

const json& swarm_answer(const json& episode) {
  const json& obs = episode["dialogue"][0]["obs"];
  EXPECT_EQ(obs.size(), 3u) << obs.dump();
  return obs[2];
}

int breaches(const json& episode) {
  int n = 0;
  for (const auto& ev : episode["_rig"]["safety_events"]) {
    if (ev["kind"] == "separation_breach" && ev["detail"].get<std::string>().rfind("enter", 0) == 0) ++n;
  }
  return n;
}

// The wind the route of the agent's turn 3 (in flight) assumed.
json wind_in_flight(const json& episode) {
  for (const auto& turn : episode["dialogue"]) {
    if (turn["speaker"] == "agent" && turn["turn"] == 3 && !turn["obs"].empty()) return turn["obs"][0]["result"]["wind"];
  }
  ADD_FAILURE() << "no observation in turn 3";
  return json();
}

// When the vehicle flew past x = 250 (the patrol's line), from the 1 Hz trajectory.
double crossing_time_s(const json& episode) {
  for (const auto& row : episode["_rig"]["trajectory"]["samples_1hz"]) {
    if (row[1].get<double>() >= 250.0) return row[0].get<double>();
  }
  return -1.0;
}

// The scenario is a test of the wind only if the commanded speed would have seen no conflict:
// the same prediction with the vehicle flying its 9 m/s over the ground (climb spread over the
// leg, as the tool server predicts) passes the patrol more than 40 m away.
TEST(WindConflict, AtTheCommandedSpeedTheScenarioLooksClear) {
  const rigs::Scenario s = rigs::load_scenario(std::string(A3_SOURCE_DIR) + "/tests/data/scenarios/headwind-crossing.json",
                                               a3::test::shared_dir());
  ASSERT_EQ(s.airspace.traffic.size(), 1u);
  const double asked_s = 2.0;
  const double leg_s = (kMast_W_m - kHome_W_m).head<2>().norm() / kCommanded_mps + kMast_W_m.z() / 2.0;
  agent::TrafficPlan commanded;
  commanded.id = "self";
  commanded.path = {{asked_s, kHome_W_m}, {asked_s + leg_s, kMast_W_m}};
  const vehicle::Approach a = vehicle::closest_approach(commanded, s.airspace.traffic[0], asked_s, 60.0);
  EXPECT_GT(a.distance_m, 40.0);
}

TEST(WindConflict, TheHeadwindPredictionCallsTheConflictThatThenHappensWithoutAvoidance) {
  const RunResult r = fly("query");
  const json& answer = swarm_answer(r.episode);
  const json& peer = answer["payload"]["peers"][0];
  EXPECT_EQ(answer["payload"]["clear"], false) << answer.dump();
  EXPECT_EQ(peer["conflict"], true) << answer.dump();
  EXPECT_LT(peer["predicted_min_separation_m"].get<double>(), 30.0) << answer.dump();
  // The predicted meeting is about when the vehicle reached the patrol's line (62 s with seed
  // 42: the gusts averaged more than the 7 m/s forecast the prediction on the ground used); at
  // the commanded speed it would have been predicted at 24 s.
  const double asked_s = r.episode["_rig"]["turns"][0]["finished_s"].get<double>();
  EXPECT_NEAR(asked_s + peer["time_to_closest_s"].get<double>(), crossing_time_s(r.episode), 15.0) << answer.dump();
  // The answer says why: our track was timed at the 3.5 m/s the Iris makes good into the 7 m/s
  // forecast headwind (10.5 m/s of air speed), not at the commanded 9 m/s.
  const json& own = answer["payload"]["own_track"];
  EXPECT_EQ(own.value("basis", ""), "route") << own.dump();
  EXPECT_EQ(own.value("commanded_speed_mps", 0.0), kCommanded_mps) << own.dump();
  EXPECT_NEAR(own.value("ground_speed_mps", 0.0), 10.5 - 7.0, 0.1) << own.dump();
  EXPECT_EQ(own["wind"].value("source", ""), "forecast") << own.dump();
  EXPECT_NEAR(own["wind"].value("speed_mps", 0.0), 7.0, 0.05) << own.dump();
  EXPECT_NEAR(own["wind"].value("from_deg", 0.0), 90.0, 0.5) << own.dump();
  EXPECT_TRUE(r.episode["final_state"]["safety_flags"]["separation_breach"].get<bool>());
  EXPECT_GE(breaches(r.episode), 1);
  // In flight the estimate comes from the drag balance: the forecast 7 m/s from the east, plus
  // what the gusts add on average.
  const json wind = wind_in_flight(r.episode);
  EXPECT_EQ(wind.value("source", ""), "telemetry") << wind.dump();
  EXPECT_NEAR(wind.value("speed_mps", 0.0), 7.5, 1.5) << wind.dump();
  EXPECT_NEAR(wind.value("from_deg", 0.0), 90.0, 15.0) << wind.dump();
}

TEST(WindConflict, AskingThePatrolToYieldOnThatPredictionAvoidsTheBreach) {
  const RunResult r = fly("yield");
  const json& peer = swarm_answer(r.episode)["payload"]["peers"][0];
  EXPECT_EQ(peer["conflict"], true) << peer.dump();
  EXPECT_EQ(peer["action"], "yielding") << peer.dump();
  EXPECT_GT(crossing_time_s(r.episode), 0.0) << "the vehicle flew on through the crossing";
  EXPECT_FALSE(r.episode["final_state"]["safety_flags"]["separation_breach"].get<bool>());
  EXPECT_EQ(breaches(r.episode), 0);
}

}  // namespace
}  // namespace a3::rigs
