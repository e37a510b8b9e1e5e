// The airspace monitor fed true vehicle states and peer traffic in virtual time: no-fly-zone
// intrusions, separation breaches, geofence exits and altitude violations appear (with an
// event when they start and one when they end) when the trajectory violates them and not
// otherwise; climbing out near the take-off point and descending to land are not violations.
#include <gtest/gtest.h>

#include <map>

#include <functional>

#include "common/channels.hpp"
#include "common/runtime.hpp"
#include "tests/vehicle/vehicle_test_util.hpp"
#include "vehicle/airspace_monitor_node.hpp"

namespace a3::vehicle {
namespace {

// A trajectory: position as a function of time, velocity by finite difference.
using Trajectory = std::function<Eigen::Vector3d(double t_s)>;

struct Flight {
  Trajectory p;
  std::function<bool(double t_s)> on_ground = [](double) { return false; };
};

// Feeds states at 50 Hz (and peers at 10 Hz) from t = 0 to end_s; returns the events.
class Feeder final : public common::Node {
 public:
  Feeder(Flight flight, std::vector<std::pair<std::string, Trajectory>> peers, double end_s)
      : flight_(std::move(flight)), peers_(std::move(peers)), end_s_(end_s) {}
  std::string name() const override { return "feeder"; }
  void start(common::Executor& executor, common::Bus& bus) override {
    executor.schedule(0, 20'000, [this, &executor, &bus] {
      const double t = executor.clock().now_s();
      if (t > end_s_) return;
      a3lcm::vehicle_state_t s{};
      s.utime_us = executor.clock().now_us();
      const Eigen::Vector3d p = flight_.p(t), v = (flight_.p(t + 0.01) - p) / 0.01;
      for (int k = 0; k < 3; ++k) {
        s.p_W_m[k] = p[k];
        s.v_W_mps[k] = v[k];
      }
      s.q_WB[0] = 1.0;
      s.on_ground = flight_.on_ground(t);
      s.crashed = crash_at_s_ >= 0.0 && t >= crash_at_s_;
      bus.publish(common::channels::kState.of(0), s);
    });
    executor.schedule(0, 100'000, [this, &executor, &bus] {
      const double t = executor.clock().now_s();
      if (t > end_s_) return;
      for (const auto& [id, traj] : peers_) {
        a3lcm::traffic_state_t m{};
        m.utime_us = executor.clock().now_us();
        m.id = id;
        const Eigen::Vector3d p = traj(t), v = (traj(t + 0.01) - p) / 0.01;
        for (int k = 0; k < 3; ++k) {
          m.p_W_m[k] = p[k];
          m.v_W_mps[k] = v[k];
        }
        m.status = "en_route";
        bus.publish(common::channels::kTraffic, m);
      }
    });
  }
  double crash_at_s_ = -1.0;

 private:
  Flight flight_;
  std::vector<std::pair<std::string, Trajectory>> peers_;
  double end_s_;
};

struct Outcome {
  std::map<std::string, uint64_t> counts;
  std::vector<a3lcm::safety_event_t> events;  // as published on A3_SAFETY
  std::map<std::string, double> closest;
};

Outcome run(Feeder& feeder, double end_s, AirspaceMonitorConfig config = {}) {
  if (config.airspace.geofence.empty()) config.airspace = test::test_airspace();
  AirspaceMonitorNode monitor(config);
  common::VirtualRuntime rt;
  Outcome out;
  rt.bus().subscribe<a3lcm::safety_event_t>(common::channels::kSafety.of(0),
                                            [&out](const a3lcm::safety_event_t& e, int64_t) { out.events.push_back(e); });
  rt.add(monitor);
  rt.add(feeder);
  rt.run_until(static_cast<int64_t>(end_s * 1e6) + 100'000);
  for (const auto& [name, value] : monitor.counters().snapshot()) out.counts[name] = value;
  out.closest = monitor.closest_approach_m();
  EXPECT_EQ(monitor.events().size(), out.events.size());
  return out;
}

// Straight line from a to b over [0, duration_s], then holding at b.
Trajectory line(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double duration_s) {
  return [=](double t) { return Eigen::Vector3d(a + (b - a) * std::clamp(t / duration_s, 0.0, 1.0)); };
}

TEST(AirspaceMonitor, AnIntrusionIntoANoFlyZoneGivesAnEnterAndALeaveEvent) {
  // Through the cylinder (200, 150) r 30 along y = 150 at 10 m/s.
  Feeder feeder({line({100, 150, 40}, {300, 150, 40}, 20.0)}, {}, 22.0);
  const auto out = run(feeder, 22.0);
  EXPECT_EQ(out.counts.at("nfz_intrusion"), 1u);
  ASSERT_EQ(out.events.size(), 2u);
  const auto& enter = out.events[0];
  EXPECT_EQ(enter.kind, "nfz_intrusion");
  EXPECT_EQ(enter.source, "airspace_monitor");
  EXPECT_EQ(enter.detail.rfind("enter: no-fly zone nfz-c", 0), 0u) << enter.detail;
  EXPECT_NEAR(static_cast<double>(enter.utime_us) * 1e-6, 7.0, 0.03) << "x = 170 m at t = 7 s";
  EXPECT_LT(enter.p_W_m[0], 170.3);
  const auto& leave = out.events[1];
  EXPECT_EQ(leave.kind, "nfz_intrusion");
  EXPECT_EQ(leave.detail.rfind("leave: no-fly zone nfz-c", 0), 0u) << leave.detail;
  EXPECT_NEAR(leave.value, 30.0, 0.01) << "deepest: the centre";
  EXPECT_NEAR(static_cast<double>(leave.utime_us) * 1e-6, 13.05, 0.03) << "0.5 m past the far edge";
}

TEST(AirspaceMonitor, PassingBesideOrAboveAZoneIsNoIntrusion) {
  Feeder beside({line({100, 185, 40}, {300, 185, 40}, 20.0)}, {}, 22.0);  // 5 m clear of the cylinder
  EXPECT_EQ(run(beside, 22.0).events.size(), 0u);
  Feeder above({line({280, 60, 70}, {360, 60, 70}, 10.0)}, {}, 12.0);  // over the square zone (ceiling 60 m)
  EXPECT_EQ(run(above, 12.0).events.size(), 0u);
  Feeder through({line({280, 60, 50}, {360, 60, 50}, 10.0)}, {}, 12.0);  // below its ceiling
  EXPECT_EQ(run(through, 12.0).counts.at("nfz_intrusion"), 1u);
}

TEST(AirspaceMonitor, ASeparationBreachIsMeasuredAgainstThePeersMinimum) {
  AirspaceMonitorConfig config;
  config.airspace = test::test_airspace();
  TrafficPlan plan;
  plan.id = "uav-2";
  plan.min_separation_m = 30.0;
  config.airspace.traffic = {plan};
  const Trajectory peer = [](double) { return Eigen::Vector3d(150, 100, 40); };
  // Passing 20 m from the peer: a breach, 20 m at its worst.
  Feeder close({line({100, 80, 40}, {200, 80, 40}, 10.0)}, {{"uav-2", peer}}, 12.0);
  const auto out = run(close, 12.0, config);
  EXPECT_EQ(out.counts.at("separation_breach"), 1u);
  ASSERT_EQ(out.events.size(), 2u);
  EXPECT_EQ(out.events[0].kind, "separation_breach");
  EXPECT_NEAR(out.events[0].value, 30.0, 0.3) << "the distance when it began";
  EXPECT_NE(out.events[0].detail.find("peer uav-2"), std::string::npos);
  EXPECT_NEAR(out.events[1].value, 20.0, 0.01) << "the closest it came";
  EXPECT_NEAR(out.closest.at("uav-2"), 20.0, 0.01);
  // Passing 40 m away: none, though the closest approach is recorded.
  Feeder far({line({100, 60, 40}, {200, 60, 40}, 10.0)}, {{"uav-2", peer}}, 12.0);
  const auto ok = run(far, 12.0, config);
  EXPECT_EQ(ok.counts.at("separation_breach"), 0u);
  EXPECT_TRUE(ok.events.empty());
  EXPECT_NEAR(ok.closest.at("uav-2"), 40.0, 0.01);
}

TEST(AirspaceMonitor, PeersNotInThePlanUseTheDefaultSeparation) {
  AirspaceMonitorConfig config;
  config.default_min_separation_m = 50.0;
  const Trajectory peer = [](double t) { return Eigen::Vector3d(200 - 10 * t, 60, 40); };  // coming at us
  Feeder feeder({[](double) { return Eigen::Vector3d(100, 100, 40); }}, {{"stranger", peer}}, 12.0);
  const auto out = run(feeder, 12.0, config);
  EXPECT_EQ(out.counts.at("separation_breach"), 1u);
  EXPECT_NEAR(out.closest.at("stranger"), 40.0, 0.05);
}

TEST(AirspaceMonitor, ClimbingOutAndLandingAreNotAltitudeViolations) {
  // Take off at (20, 20), climb to 40 m, fly to (200, 60), descend vertically and land there.
  const Trajectory p = [](double t) {
    if (t < 20.0) return Eigen::Vector3d(20, 20, 2.0 * t);
    if (t < 56.0) return Eigen::Vector3d(20 + 5.0 * (t - 20.0), 20 + (40.0 / 36.0) * (t - 20.0), 40.0);
    return Eigen::Vector3d(200, 60, std::max(40.0 - 1.0 * (t - 56.0), 0.0));
  };
  Flight flight{p, [&p](double t) { return t <= 0.0 || p(t).z() <= 0.0; }};
  Feeder feeder(flight, {}, 100.0);
  const auto out = run(feeder, 100.0);
  EXPECT_EQ(out.counts.at("altitude_violation"), 0u);
  EXPECT_TRUE(out.events.empty()) << out.events.front().detail;
}

TEST(AirspaceMonitor, FlyingBelowTheMinimumAwayFromTheTakeOffPointIsAViolation) {
  // Take off, then fly out at 6 m (the minimum is 10 m), climb back to 30 m.
  const Trajectory p = [](double t) {
    if (t < 3.0) return Eigen::Vector3d(20, 20, 2.0 * t);
    if (t < 23.0) return Eigen::Vector3d(20 + 5.0 * (t - 3.0), 20, 6.0);
    return Eigen::Vector3d(120, 20, std::min(6.0 + 2.0 * (t - 23.0), 30.0));
  };
  Feeder feeder({p}, {}, 40.0);
  const auto out = run(feeder, 40.0);
  EXPECT_EQ(out.counts.at("altitude_violation"), 1u);
  ASSERT_EQ(out.events.size(), 2u);
  EXPECT_EQ(out.events[0].kind, "altitude_violation");
  EXPECT_NE(out.events[0].detail.find("below the minimum 10.0 m at 6.00 m"), std::string::npos) << out.events[0].detail;
  EXPECT_NEAR(out.events[0].p_W_m[0], 35.0, 0.2) << "15 m from the take-off point";
  EXPECT_EQ(out.events[1].detail.rfind("leave: ", 0), 0u);
  EXPECT_NEAR(static_cast<double>(out.events[1].utime_us) * 1e-6, 23.0, 0.05)
      << "the climb back is a vertical transit";
}

TEST(AirspaceMonitor, AboveTheMaximumIsAlwaysAViolation) {
  const Trajectory p = [](double t) { return Eigen::Vector3d(100, 100, 100.0 + 2.0 * std::min(t, 15.0)); };
  Feeder feeder({p}, {}, 20.0);
  const auto out = run(feeder, 20.0);
  EXPECT_EQ(out.counts.at("altitude_violation"), 1u);
  ASSERT_EQ(out.events.size(), 1u) << "still above at the end";
  EXPECT_NE(out.events[0].detail.find("above the maximum 120.0 m"), std::string::npos);
}

TEST(AirspaceMonitor, LeavingTheGeofenceAndCrashing) {
  Feeder feeder({line({380, 100, 40}, {420, 100, 40}, 8.0)}, {}, 10.0);
  feeder.crash_at_s_ = 9.0;
  const auto out = run(feeder, 10.0);
  EXPECT_EQ(out.counts.at("geofence_exit"), 1u);
  EXPECT_EQ(out.counts.at("crash"), 1u);
  ASSERT_EQ(out.events.size(), 2u);
  EXPECT_EQ(out.events[0].kind, "geofence_exit");
  EXPECT_NEAR(static_cast<double>(out.events[0].utime_us) * 1e-6, 4.0, 0.03);
  EXPECT_EQ(out.events[1].kind, "crash");
}

TEST(AirspaceMonitor, BadConfigIsRefusedNamingTheField) {
  AirspaceMonitorConfig config;
  config.hysteresis_m = -1.0;
  try {
    AirspaceMonitorNode node(config);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("AirspaceMonitorConfig.hysteresis_m"), std::string::npos);
  }
}

}  // namespace
}  // namespace a3::vehicle
