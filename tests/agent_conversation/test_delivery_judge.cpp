// A delivery is judged as its brief says (issue 34): the brief states the drop rule with the
// flight controller's hover tolerance, a vehicle that settles at the drop altitude delivers, and
// one that stays above it is told why not, by the tracker and the supervisor.
#include <gtest/gtest.h>

#include "agent/conversation/simulated_user.hpp"
#include "agent/mission/mission_tracker.hpp"
#include "agent/mission/objective_rules.hpp"

namespace a3::agent {
namespace {

Mission delivery_mission() {
  Mission m;
  m.name = "drop";
  m.description = "deliver";
  Objective o;
  o.id = "drop-point";
  o.type = ObjectiveType::kDelivery;
  o.point = {600.0, 400.0};
  o.radius_m = 15.0;
  o.drop_altitude_m = 8.0;
  m.objectives.push_back(o);
  return m;
}

// Hovers at (x, y, z) from t0 for duration_s, 10 Hz states.
void hover(MissionTracker& tracker, double x, double y, double z, double t0_s, double duration_s) {
  for (double t = t0_s; t <= t0_s + duration_s + 1e-9; t += 0.1) {
    a3lcm::vehicle_state_t s{};
    s.utime_us = static_cast<int64_t>(t * 1e6);
    s.p_W_m[0] = x;
    s.p_W_m[1] = y;
    s.p_W_m[2] = z;
    tracker.on_state(s);
  }
}

TEST(DeliveryJudge, TheBriefStatesTheRuleTheJudgeApplies) {
  const nlohmann::json brief = mission_brief_json(delivery_mission());
  const std::string rule = brief["objectives"][0]["judged"];
  EXPECT_NE(rule.find("within 15 m"), std::string::npos) << rule;
  EXPECT_NE(rule.find("at or below 8.5 m"), std::string::npos) << rule;
  EXPECT_NE(rule.find("for 1 s"), std::string::npos) << rule;
  EXPECT_NE(rule.find("no release tool"), std::string::npos) << rule;
}

TEST(DeliveryJudge, AVehicleSettledAtTheDropAltitudeDelivers) {
  MissionTracker tracker(delivery_mission());
  hover(tracker, 605.0, 402.0, 8.001, 10.0, 1.5);
  ASSERT_TRUE(tracker.progress()[0].done);
  EXPECT_NEAR(tracker.progress()[0].done_at_s, 11.0, 0.15);
  EXPECT_EQ(tracker.to_json()["objectives"][0].count("why_not"), 0u);
}

TEST(DeliveryJudge, AVehicleAboveTheToleranceIsToldTheAltitudeItReached) {
  MissionTracker tracker(delivery_mission());
  hover(tracker, 100.0, 100.0, 30.0, 0.0, 2.0);
  EXPECT_EQ(tracker.why_not_done(0), "") << "never near the drop point: nothing to explain yet";
  hover(tracker, 600.0, 400.0, 8.6, 10.0, 3.0);
  EXPECT_FALSE(tracker.progress()[0].done);
  const std::string why = tracker.to_json()["objectives"][0].value("why_not", "");
  EXPECT_NE(why.find("lowest altitude within 15 m of the drop point was 8.6 m"), std::string::npos) << why;
  EXPECT_NE(why.find("8.5 m or lower"), std::string::npos) << why;

  SimulatedUser supervisor;
  SupervisorView first;
  supervisor.speak(first);  // the start confirmation
  SupervisorView view;
  view.progress = tracker.to_json();
  view.landed_after_flight = true;
  const UserUtterance u = supervisor.speak(view);
  EXPECT_NE(u.text.find("Not done: drop-point (not delivered: the lowest altitude"), std::string::npos) << u.text;
}

TEST(DeliveryJudge, AStayTooShortIsNamedAsSuch) {
  MissionTracker tracker(delivery_mission());
  hover(tracker, 600.0, 400.0, 7.0, 10.0, 0.5);
  hover(tracker, 600.0, 400.0, 12.0, 10.6, 1.0);
  EXPECT_FALSE(tracker.progress()[0].done);
  const std::string why = tracker.why_not_done(0);
  EXPECT_NE(why.find("for 0.5 s at most"), std::string::npos) << why;
}

}  // namespace
}  // namespace a3::agent
