// The real-time accounting and contract of an episode (rigs/run/realtime_report): what breaks
// the contract in lockstep (only a wall-clock agent's distorted latency) and free-running (a late
// host), the window meter, and the counters made from the nodes' statistics.
#include <gtest/gtest.h>

#include "rigs/run/realtime_report.hpp"

namespace a3::rigs {
namespace {

NodeStatsRecord node(nlohmann::json counters, nlohmann::json timing) {
  NodeStatsRecord r;
  r.stats = {{"counters", std::move(counters)}, {"timing", std::move(timing)}};
  r.final = true;
  return r;
}

std::map<std::string, NodeStatsRecord> vehicle(double fc_misses, double fc_steps, bool lockstep) {
  nlohmann::json dyn_timing = {{"timers_run", 1000.0}, {"lateness_p99_us", 50.0}, {"deadline_misses", 0.0}};
  if (lockstep) {
    dyn_timing.update({{"lockstep_grants", 1000.0}, {"lockstep_waits", 12.0}, {"lockstep_wait_total_s", 0.5},
                       {"lockstep_wait_max_s", 0.1}, {"lockstep_lag_dropped_s", 0.0}, {"worst_window_rtf", 3.5}});
  }
  return {{"dynamics", node({{"steps", 1000}, {"stale_steps", lockstep ? 0 : 7}}, dyn_timing)},
          {"fc", node({{"steps", 1000}}, {{"timers_run", fc_steps}, {"lateness_p99_us", 900.0},
                                          {"deadline_misses", fc_misses}})}};
}

RunOptions options(Sync sync, const std::string& agent, double rtf) {
  RunOptions o;
  o.sync = sync;
  o.agent = agent;
  o.real_time_factor = rtf;
  return o;
}

TEST(RealTimeReport, InLockstepASlowHostDoesNotBreakTheContractOfASimulatedTimeAgent) {
  const auto r = realtime_report(options(Sync::kLockstep, "scripted", 4.0), {100.0, 60.0, 1.2}, vehicle(0, 1000, true));
  EXPECT_EQ(r["sync"], "lockstep");
  EXPECT_NEAR(r["rtf"]["achieved"].get<double>(), 100.0 / 60.0, 1e-12);
  EXPECT_DOUBLE_EQ(r["rtf"]["worst_window"].get<double>(), 1.2);
  EXPECT_FALSE(r["contract"]["violated"].get<bool>()) << r.dump();
  EXPECT_EQ(r["lockstep"]["waits"].get<double>(), 12.0);
  EXPECT_EQ(r["stale_steps"].get<int>(), 0);
  EXPECT_EQ(realtime_violations(r), "");
}

TEST(RealTimeReport, InLockstepAWallClockAgentNeedsTheRequestedFactor) {
  // An LLM's latency is charged at the achieved factor: 25 % off the requested one is a broken run.
  auto r = realtime_report(options(Sync::kLockstep, "llm", 4.0), {300.0, 100.0, 2.0}, vehicle(0, 1000, true));
  EXPECT_TRUE(r["contract"]["violated"].get<bool>());
  EXPECT_NE(realtime_violations(r).find("measured on the wall clock"), std::string::npos) << r.dump();
  r = realtime_report(options(Sync::kLockstep, "llm", 4.0), {395.0, 100.0, 3.9}, vehicle(0, 1000, true));
  EXPECT_FALSE(r["contract"]["violated"].get<bool>()) << r.dump();
}

TEST(RealTimeReport, FreeRunningALateHostBreaksTheContract) {
  auto r = realtime_report(options(Sync::kFree, "scripted", 4.0), {300.0, 100.0, 2.0}, vehicle(0, 1000, false));
  EXPECT_TRUE(r["contract"]["violated"].get<bool>());
  EXPECT_NE(realtime_violations(r).find("below 0.90 x"), std::string::npos) << realtime_violations(r);
  EXPECT_EQ(r["stale_steps"].get<int>(), 7);
  r = realtime_report(options(Sync::kFree, "scripted", 4.0), {399.0, 100.0, 3.9}, vehicle(20, 1000, false));
  EXPECT_NE(realtime_violations(r).find("fc missed 2.0 % of its deadlines"), std::string::npos) << realtime_violations(r);
  r = realtime_report(options(Sync::kFree, "scripted", 4.0), {399.0, 100.0, 3.9}, vehicle(5, 1000, false));
  EXPECT_FALSE(r["contract"]["violated"].get<bool>()) << r.dump();
  EXPECT_TRUE(r["lockstep"].is_null());
}

TEST(RealTimeReport, TheSummaryLineSaysWhatHappened) {
  const auto r = realtime_report(options(Sync::kLockstep, "scripted", 4.0), {100.0, 25.0, 3.9}, vehicle(0, 1000, true));
  const std::string line = realtime_summary(r);
  EXPECT_NE(line.find("lockstep, achieved 4.000 of 4.000"), std::string::npos) << line;
  EXPECT_NE(line.find("lockstep waits 12 (0.50 s)"), std::string::npos) << line;
  EXPECT_NE(line.find("vehicle step lateness p99 0.90 ms"), std::string::npos) << line;
  EXPECT_NE(line.find("contract kept"), std::string::npos) << line;
}

TEST(WindowMeter, KeepsTheLowestWholeWindow) {
  WindowMeter m(1.0);
  m.sample(0.0, 0.0);
  m.sample(0.5, 2.0);
  EXPECT_LT(m.worst(), 0.0);  // no whole window yet
  m.sample(1.0, 4.0);         // 4 s in 1 s
  m.sample(2.5, 5.0);         // 1 s in 1.5 s
  m.sample(3.5, 9.0);         // 4 s in 1 s
  EXPECT_NEAR(m.worst(), 1.0 / 1.5, 1e-12);
}

TEST(CountersFromStats, AreTheNodesCountersByName) {
  const auto c = counters_from_stats(vehicle(0, 1000, true));
  EXPECT_EQ(c["dynamics"]["steps"], 1000);
  EXPECT_EQ(c["fc"]["steps"], 1000);
  EXPECT_FALSE(c.contains("timing"));
}

}  // namespace
}  // namespace a3::rigs
