// read_telemetry's wind and leg in a whole episode (issue 15): the vehicle flies out along x and
// back in a steady 6 m/s wind from the north-east (Dryden turbulence on top), reading the
// telemetry every 7 s. Each reading in level flight, once the estimate is learned in flight,
// must give the scenario's wind within the estimator's tolerance, the ground speed the vehicle
// then really makes good (below the commanded 9 m/s into the wind, the command itself with it
// behind), the headwind and crosswind with their signs, and an ETA that the vehicle keeps.
// Scenario: tests/data/scenarios/steady-diagonal-wind.json.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "agent/conversation/agent.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

using nlohmann::json;

const Eigen::Vector3d kFar_W_m(400, 300, 20), kHome_W_m(100, 300, 20);
constexpr double kCommanded_mps = 9.0;
constexpr double kWind_mps = 6.0, kWindFrom_deg = 45.0;
const double kAlongX_mps = kWind_mps / std::sqrt(2.0);  // the wind's component along x and across it

// One turn: takes off and flies out and back at 9 m/s, then reads the telemetry every 7 s (steps
// of the same turn: the user's next turn waits for the motion to end; at most 14 readings, the
// turn's cap is 16 actions) until the route is done.
class TelemetryAgent final : public agent::Agent {
 public:
  std::string name() const override { return "wind-telemetry-test"; }
  agent::AgentDecision decide(const agent::AgentContext& context) override {
    agent::AgentDecision d;
    if (context.turn_number > 1) {
      d.intent = "monitor";
      d.text = "Done.";
      return d;
    }
    d.turn_continues = true;
    if (context.step == 1) {
      d.intent = "navigate_to_target";
      d.text = "Out and back along the wind.";
      d.actions = json::array(
          {{{"type", "mcp"}, {"name", "takeoff"}, {"args", {{"altitude_m", kFar_W_m.z()}}}},
           {{"type", "mcp"},
            {"name", "navigate_to"},
            {"args", {{"waypoints", {point(kFar_W_m), point(kHome_W_m)}}, {"speed_mps", kCommanded_mps}}}}});
      return d;
    }
    const json& last = context.turn_obs.back();
    d.turn_continues = context.step < 15 && (context.step == 2 || !last["result"]["route"].is_null());
    d.think_time_s = 7.0;
    d.actions = json::array({{{"type", "mcp"}, {"name", "read_telemetry"}, {"args", json::object()}}});
    return d;
  }

 private:
  static json point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
};

json fly() {
  RunOptions o = a3::test::virtual_run(std::string(A3_SOURCE_DIR) + "/tests/data/scenarios/steady-diagonal-wind.json",
                                       "wind-telemetry");
  o.agent_factory = [] { return std::make_unique<TelemetryAgent>(); };
  RunResult r = a3::test::run(o);
  std::filesystem::remove_all(o.out_dir);
  return r.episode;
}

// The readings taken in steady level flight (more than 40 m from either end of the line flown,
// past the acceleration and before the slowing down), after the estimate was learned in flight.
std::vector<json> level_flight_readings(const json& episode) {
  std::vector<json> out;
  for (const auto& turn : episode["dialogue"]) {
    for (const auto& obs : turn["obs"]) {
      if (obs.value("tool", "") != "read_telemetry") continue;
      const json& t = obs["result"];
      if (t["leg"].is_null() || t["leg"]["course_deg"].is_null()) continue;
      const Eigen::Vector3d p(t["pose"]["x"].get<double>(), t["pose"]["y"].get<double>(), t["pose"]["z"].get<double>());
      if (t["wind"]["source"] != "telemetry" || std::abs(p.z() - kFar_W_m.z()) > 1.0) continue;
      if ((p - kFar_W_m).head<2>().norm() < 40.0 || (p - kHome_W_m).head<2>().norm() < 40.0) continue;
      out.push_back(t);
    }
  }
  return out;
}

// The true horizontal position at t_s, interpolated in the 1 Hz trajectory.
Eigen::Vector2d true_position_at(const json& episode, double t_s) {
  const json& rows = episode["_rig"]["trajectory"]["samples_1hz"];
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double t0 = rows[i - 1][0].get<double>(), t1 = rows[i][0].get<double>();
    if (t1 < t_s) continue;
    const double a = (t_s - t0) / (t1 - t0);
    const Eigen::Vector2d p0(rows[i - 1][1].get<double>(), rows[i - 1][2].get<double>());
    const Eigen::Vector2d p1(rows[i][1].get<double>(), rows[i][2].get<double>());
    return p0 + a * (p1 - p0);
  }
  ADD_FAILURE() << "no trajectory at " << t_s << " s";
  return Eigen::Vector2d::Zero();
}

// When the vehicle first came within 3 m of target (horizontally) after t_s, from the 1 Hz trajectory.
double arrival_s(const json& episode, double t_s, const Eigen::Vector2d& target) {
  for (const auto& row : episode["_rig"]["trajectory"]["samples_1hz"]) {
    const double t = row[0].get<double>();
    if (t > t_s && (Eigen::Vector2d(row[1].get<double>(), row[2].get<double>()) - target).norm() < 3.0) return t;
  }
  return -1.0;
}

// What the vehicle made good along the leg's course over the 6 s after the reading.
double made_good_mps(const json& episode, const json& reading) {
  const double t_s = reading["time_s"].get<double>(), course = reading["leg"]["course_deg"].get<double>() * M_PI / 180.0;
  const Eigen::Vector2d u(std::cos(course), std::sin(course));
  return u.dot(true_position_at(episode, t_s + 6.0) - true_position_at(episode, t_s)) / 6.0;
}

void expect_the_estimated_wind(const json& wind) {
  EXPECT_NEAR(wind["speed_mps"].get<double>(), kWind_mps, 1.0) << wind.dump();
  EXPECT_NEAR(wind["from_deg"].get<double>(), kWindFrom_deg, 10.0) << wind.dump();
  EXPECT_GT(wind["learned_s"].get<double>(), 5.0) << wind.dump();
  EXPECT_LT(wind["age_s"].get<double>(), 1.0) << "the estimate follows the states in flight: " << wind.dump();
}

void expect_eta_kept(const json& episode, const json& reading) {
  const json& leg = reading["leg"];
  const double eta_s = leg["eta_s"].get<double>();
  // A level leg: the ETA is the distance at the ground speed it reports.
  EXPECT_NEAR(eta_s, leg["distance_m"].get<double>() / leg["ground_speed_mps"].get<double>(), 0.2) << leg.dump();
  const Eigen::Vector2d target(leg["target"]["x"].get<double>(), leg["target"]["y"].get<double>());
  const double flown_s = arrival_s(episode, reading["time_s"].get<double>(), target) - reading["time_s"].get<double>();
  ASSERT_GT(flown_s, 0.0) << "the vehicle never reached " << leg.dump();
  // The fc slows down for the waypoint in its last metres: a few seconds more than the leg's ETA.
  EXPECT_NEAR(flown_s, eta_s, 0.1 * eta_s + 3.0) << leg.dump();
}

TEST(WindTelemetry, ReadTelemetryReportsTheWindAndWhatTheVehicleMakesGoodOnEachLeg) {
  const json episode = fly();
  int into_wind = 0, downwind = 0;
  for (const json& reading : level_flight_readings(episode)) {
    SCOPED_TRACE(reading.dump());
    const json& leg = reading["leg"];
    expect_the_estimated_wind(reading["wind"]);
    EXPECT_EQ(leg["kind"], "route");
    EXPECT_EQ(leg["commanded_speed_mps"], kCommanded_mps);
    const double ground_mps = leg["ground_speed_mps"].get<double>();
    EXPECT_NEAR(ground_mps, made_good_mps(episode, reading), 0.75) << "what the vehicle then flew";
    const double course_deg = leg["course_deg"].get<double>();
    if (std::abs(course_deg) < 5.0) {  // east, into the wind from the north-east: from the left
      ++into_wind;
      EXPECT_LT(ground_mps, kCommanded_mps - 2.0);
      EXPECT_NEAR(leg["headwind_mps"].get<double>(), kAlongX_mps, 1.0);
      EXPECT_NEAR(leg["crosswind_mps"].get<double>(), -kAlongX_mps, 1.0);
    } else if (std::abs(course_deg) > 175.0) {  // west, with the wind behind, from the right
      ++downwind;
      EXPECT_EQ(ground_mps, kCommanded_mps);
      EXPECT_NEAR(leg["headwind_mps"].get<double>(), -kAlongX_mps, 1.0);
      EXPECT_NEAR(leg["crosswind_mps"].get<double>(), kAlongX_mps, 1.0);
    } else {
      ADD_FAILURE() << "a course off the x axis";
    }
    expect_eta_kept(episode, reading);
  }
  EXPECT_GE(into_wind, 2) << "readings on the way out";
  EXPECT_GE(downwind, 1) << "readings on the way back";
}

}  // namespace
}  // namespace a3::rigs
